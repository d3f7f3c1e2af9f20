$d0_uniform << EOD
0.050100 1.756580 "2x2"
0.050330 3.550833 "1x1"
0.077987 1.143715 "3x3"
0.086473 0.871528 "4x4"
0.097695 0.698281 "5x5"
0.151919 0.573628 "6x6"
0.257284 0.432014 "8x8"
EOD
$d0_stratified << EOD
0.051884 3.591788 "1x1"
0.060311 0.958420 "2x2"
0.082974 0.445330 "3x3"
0.111121 0.263455 "4x4"
0.135477 0.122587 "6x6"
0.146132 0.173247 "5x5"
0.305356 0.070104 "8x8"
EOD
$d0_adaptive << EOD
0.037779 3.591788 "1x1"
0.041559 0.958420 "2x2"
0.047488 0.445330 "3x3"
0.065542 0.263455 "4x4"
0.078028 0.173247 "5x5"
0.099600 0.122587 "6x6"
0.178198 0.070104 "8x8"
EOD
$d1_uniform << EOD
0.008911 9.102187 "1x1"
0.011394 4.521163 "2x2"
0.024910 2.987153 "3x3"
0.037080 2.254983 "4x4"
0.053087 1.820000 "5x5"
0.067327 1.519236 "6x6"
0.118641 1.143611 "8x8"
EOD
$d1_stratified << EOD
0.010407 9.061563 "1x1"
0.017282 2.781424 "2x2"
0.028955 1.385694 "3x3"
0.036083 0.886510 "4x4"
0.049135 0.598073 "5x5"
0.091101 0.452795 "6x6"
0.149837 0.276806 "8x8"
EOD
$d1_adaptive << EOD
0.012486 9.061563 "1x1"
0.017730 2.774132 "2x2"
0.026211 1.382778 "3x3"
0.036959 0.885833 "4x4"
0.050572 0.598594 "5x5"
0.068767 0.454618 "6x6"
0.110735 0.279097 "8x8"
EOD
$d2_uniform << EOD
0.004503 14.656852 "1x1"
0.015267 6.746759 "2x2"
0.031413 4.420833 "3x3"
0.066456 3.264491 "4x4"
0.090547 2.672222 "5x5"
0.130467 2.243681 "6x6"
EOD
$d2_stratified << EOD
0.004831 14.504907 "1x1"
0.016045 6.142662 "2x2"
0.034270 3.923148 "3x3"
0.076815 2.621991 "4x4"
0.097837 2.137014 "5x5"
0.139771 1.768681 "6x6"
EOD
$d2_adaptive << EOD
0.026234 4.000926 "a3 t8"
0.032188 3.954444 "a3 t2"
0.079783 2.195301 "a5 t2"
0.082448 2.250995 "a5 t8"
0.137070 1.587222 "a7 t8"
0.144829 1.524028 "a7 t2"
0.225142 1.253981 "a9 t8"
0.238388 1.185810 "a9 t2"
EOD
set terminal pngcairo size 1800,600 font 'sans,11' background rgb 'white'
set output 'docs/soft.png.tmp'
set multiplot layout 1,3 title 'raytrace: soft shadows and depth of field, run time against error (median CPU time of >= 9 runs; error against 64x the top rung''s samples)'
set logscale xy
set grid
set xlabel 'CPU time (s)'
set ylabel 'mean absolute error (0-255 per channel)'
set key top right font ',10'
set title 'area-room (160x120, area light n x n samples)'
plot $d0_uniform using 1:2 with linespoints pt 7 ps 1.3 lc rgb '#1f77b4' title 'uniform', $d0_uniform using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#1f77b4' notitle, \
  $d0_stratified using 1:2 with linespoints pt 5 ps 1.3 lc rgb '#2ca02c' title 'stratified', $d0_stratified using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#2ca02c' notitle, \
  $d0_adaptive using 1:2 with linespoints pt 9 ps 1.3 lc rgb '#d62728' title 'adaptive', $d0_adaptive using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#d62728' notitle
set title 'ball (160x120, area light n x n samples)'
plot $d1_uniform using 1:2 with linespoints pt 7 ps 1.3 lc rgb '#1f77b4' title 'uniform', $d1_uniform using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#1f77b4' notitle, \
  $d1_stratified using 1:2 with linespoints pt 5 ps 1.3 lc rgb '#2ca02c' title 'stratified', $d1_stratified using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#2ca02c' notitle, \
  $d1_adaptive using 1:2 with linespoints pt 9 ps 1.3 lc rgb '#d62728' title 'adaptive', $d1_adaptive using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#d62728' notitle
set title 'focus (160x90, N x N pixel grid, a lens point each; aN tT: --adaptive)'
plot $d2_uniform using 1:2 with linespoints pt 7 ps 1.3 lc rgb '#1f77b4' title 'uniform', $d2_uniform using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#1f77b4' notitle, \
  $d2_stratified using 1:2 with linespoints pt 5 ps 1.3 lc rgb '#2ca02c' title 'stratified', $d2_stratified using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#2ca02c' notitle, \
  $d2_adaptive using 1:2 with linespoints pt 9 ps 1.3 lc rgb '#d62728' title 'adaptive', $d2_adaptive using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#d62728' notitle
unset multiplot
