$d0_uniform << EOD
0.032491 3.550833 "1x1"
0.038206 1.756580 "2x2"
0.054436 1.143715 "3x3"
0.070640 0.871528 "4x4"
0.090209 0.698281 "5x5"
0.121106 0.573628 "6x6"
0.248867 0.432014 "8x8"
EOD
$d0_stratified << EOD
0.037454 3.591788 "1x1"
0.051432 0.958420 "2x2"
0.073081 0.445330 "3x3"
0.091121 0.263455 "4x4"
0.116880 0.173247 "5x5"
0.139323 0.122587 "6x6"
0.245292 0.070104 "8x8"
EOD
$d0_adaptive << EOD
0.039935 3.591788 "1x1"
0.042796 0.958420 "2x2"
0.047964 0.445330 "3x3"
0.056700 0.263455 "4x4"
0.074903 0.173247 "5x5"
0.119369 0.122587 "6x6"
0.150098 0.070104 "8x8"
EOD
$d1_uniform << EOD
0.010049 9.102187 "1x1"
0.012161 4.521163 "2x2"
0.016728 2.987153 "3x3"
0.026435 2.254983 "4x4"
0.037059 1.820000 "5x5"
0.050316 1.519236 "6x6"
0.084877 1.143611 "8x8"
EOD
$d1_stratified << EOD
0.009792 9.061563 "1x1"
0.017452 2.781424 "2x2"
0.027286 1.385694 "3x3"
0.038819 0.886510 "4x4"
0.049119 0.598073 "5x5"
0.067713 0.452795 "6x6"
0.143952 0.276806 "8x8"
EOD
$d1_adaptive << EOD
0.011569 2.774132 "2x2"
0.011798 9.061563 "1x1"
0.022598 1.382778 "3x3"
0.033161 0.598594 "5x5"
0.036371 0.885833 "4x4"
0.051151 0.454618 "6x6"
0.076954 0.279097 "8x8"
EOD
$d2_uniform << EOD
0.003514 14.656852 "1x1"
0.013639 6.746759 "2x2"
0.030843 4.420833 "3x3"
0.066878 3.264491 "4x4"
0.091880 2.672222 "5x5"
0.133616 2.243681 "6x6"
EOD
$d2_stratified << EOD
0.003749 14.504907 "1x1"
0.015714 6.142662 "2x2"
0.034352 3.923148 "3x3"
0.069679 2.621991 "4x4"
0.097710 2.137014 "5x5"
0.148012 1.768681 "6x6"
EOD
$d2_adaptive << EOD
0.036205 3.960417 "a3 t8"
0.037125 3.938102 "a3 t2"
0.079898 2.178472 "a5 t8"
0.098331 2.155139 "a5 t2"
0.145556 1.470671 "a7 t2"
0.148359 1.497014 "a7 t8"
0.243162 1.124306 "a9 t2"
0.250258 1.150440 "a9 t8"
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
