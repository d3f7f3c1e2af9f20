$d0_uniform << EOD
0.037076 3.550833 "1x1"
0.047227 1.756580 "2x2"
0.070704 1.143715 "3x3"
0.107613 0.871528 "4x4"
0.125407 0.698281 "5x5"
0.168077 0.573628 "6x6"
0.188620 0.432014 "8x8"
EOD
$d0_stratified << EOD
0.034571 3.591788 "1x1"
0.055797 0.958420 "2x2"
0.055827 0.445330 "3x3"
0.077152 0.263455 "4x4"
0.122386 0.173247 "5x5"
0.178301 0.122587 "6x6"
0.245117 0.070104 "8x8"
EOD
$d0_adaptive << EOD
0.053567 0.958420 "2x2"
0.054530 3.591788 "1x1"
0.061279 0.445330 "3x3"
0.086249 0.122587 "6x6"
0.086371 0.173247 "5x5"
0.088883 0.263455 "4x4"
0.166229 0.070104 "8x8"
EOD
$d1_uniform << EOD
0.007030 9.102187 "1x1"
0.015280 4.521163 "2x2"
0.024289 2.987153 "3x3"
0.030826 2.254983 "4x4"
0.040452 1.820000 "5x5"
0.056448 1.519236 "6x6"
0.093616 1.143611 "8x8"
EOD
$d1_stratified << EOD
0.008330 9.061563 "1x1"
0.014338 2.781424 "2x2"
0.025125 1.385694 "3x3"
0.051154 0.886510 "4x4"
0.073731 0.598073 "5x5"
0.101491 0.452795 "6x6"
0.153744 0.276806 "8x8"
EOD
$d1_adaptive << EOD
0.012457 9.061563 "1x1"
0.018236 1.382778 "3x3"
0.018657 2.774132 "2x2"
0.024732 0.885833 "4x4"
0.032716 0.598594 "5x5"
0.054298 0.454618 "6x6"
0.079916 0.279097 "8x8"
EOD
$d2_uniform << EOD
0.004345 14.656852 "1x1"
0.017322 6.746759 "2x2"
0.036174 4.420833 "3x3"
0.054753 3.264491 "4x4"
0.096408 2.672222 "5x5"
0.143698 2.243681 "6x6"
EOD
$d2_stratified << EOD
0.004932 14.504907 "1x1"
0.019808 6.142662 "2x2"
0.040982 3.923148 "3x3"
0.072882 2.621991 "4x4"
0.105833 2.137014 "5x5"
0.158842 1.768681 "6x6"
EOD
$d2_adaptive << EOD
0.028203 3.938102 "a3 t2"
0.028460 3.960417 "a3 t8"
0.078436 2.155139 "a5 t2"
0.079665 2.178472 "a5 t8"
0.151750 1.497014 "a7 t8"
0.159318 1.470671 "a7 t2"
0.250971 1.124306 "a9 t2"
0.297394 1.150440 "a9 t8"
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
