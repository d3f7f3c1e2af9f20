$d0_uniform << EOD
0.035406 3.550833 "1x1"
0.058206 1.756580 "2x2"
0.076113 1.143715 "3x3"
0.099431 0.871528 "4x4"
0.101524 0.698281 "5x5"
0.126219 0.573628 "6x6"
0.192221 0.432014 "8x8"
EOD
$d0_stratified << EOD
0.035273 3.591788 "1x1"
0.059180 0.958420 "2x2"
0.063280 0.445330 "3x3"
0.075092 0.263455 "4x4"
0.098920 0.173247 "5x5"
0.183362 0.122587 "6x6"
0.303968 0.070104 "8x8"
EOD
$d0_adaptive << EOD
0.054608 3.591788 "1x1"
0.060257 0.958420 "2x2"
0.070805 0.445330 "3x3"
0.071353 0.173247 "5x5"
0.081281 0.263455 "4x4"
0.110522 0.122587 "6x6"
0.176218 0.070104 "8x8"
EOD
$d1_uniform << EOD
0.006352 9.102187 "1x1"
0.010051 4.521163 "2x2"
0.016176 2.987153 "3x3"
0.024900 2.254983 "4x4"
0.043226 1.820000 "5x5"
0.064926 1.519236 "6x6"
0.085747 1.143611 "8x8"
EOD
$d1_stratified << EOD
0.009947 9.061563 "1x1"
0.015436 2.781424 "2x2"
0.019104 1.385694 "3x3"
0.028847 0.886510 "4x4"
0.041873 0.598073 "5x5"
0.088673 0.452795 "6x6"
0.149588 0.276806 "8x8"
EOD
$d1_adaptive << EOD
0.013960 9.061563 "1x1"
0.019198 2.774132 "2x2"
0.026308 1.382778 "3x3"
0.040035 0.885833 "4x4"
0.054638 0.598594 "5x5"
0.072224 0.454618 "6x6"
0.126819 0.279097 "8x8"
EOD
$d2_uniform << EOD
0.003140 14.660625 "1x1"
0.013151 6.744560 "2x2"
0.031836 4.419468 "3x3"
0.052091 3.256319 "4x4"
0.080529 2.677338 "5x5"
0.116093 2.240880 "6x6"
EOD
$d2_stratified << EOD
EOD
$d2_adaptive << EOD
0.017106 5.075741 "a3 t8"
0.026289 4.887616 "a3 t2"
0.058141 3.557431 "a5 t4"
0.059820 3.429861 "a5 t2"
0.065178 3.646273 "a5 t8"
0.091654 2.776551 "a7 t2"
0.096917 3.014583 "a7 t8"
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
  $d2_adaptive using 1:2 with linespoints pt 9 ps 1.3 lc rgb '#d62728' title 'adaptive', $d2_adaptive using 1:2:3 with labels left offset 0.6,0.5 font ',8' tc rgb '#d62728' notitle
unset multiplot
