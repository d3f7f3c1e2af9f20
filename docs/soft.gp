$d0_uniform << EOD
0.049639 3.550833 "1x1"
0.060835 1.756580 "2x2"
0.083596 1.143715 "3x3"
0.101610 0.871528 "4x4"
0.129644 0.698281 "5x5"
0.177304 0.573628 "6x6"
0.286327 0.432014 "8x8"
EOD
$d0_stratified << EOD
0.049481 3.591788 "1x1"
0.063890 0.958420 "2x2"
0.093145 0.445330 "3x3"
0.118602 0.263455 "4x4"
0.152012 0.173247 "5x5"
0.194792 0.122587 "6x6"
0.316035 0.070104 "8x8"
EOD
$d0_adaptive << EOD
0.057257 3.591788 "1x1"
0.063759 0.958420 "2x2"
0.076688 0.445330 "3x3"
0.088653 0.263455 "4x4"
0.106467 0.173247 "5x5"
0.126478 0.122587 "6x6"
0.183437 0.070104 "8x8"
EOD
$d1_uniform << EOD
0.010167 9.102187 "1x1"
0.015693 4.521163 "2x2"
0.024605 2.987153 "3x3"
0.035878 2.254983 "4x4"
0.052913 1.820000 "5x5"
0.058303 1.519236 "6x6"
0.115285 1.143611 "8x8"
EOD
$d1_stratified << EOD
0.011032 9.061563 "1x1"
0.017685 2.781424 "2x2"
0.028341 1.385694 "3x3"
0.044118 0.886510 "4x4"
0.064027 0.598073 "5x5"
0.087140 0.452795 "6x6"
0.148064 0.276806 "8x8"
EOD
$d1_adaptive << EOD
0.013444 9.061563 "1x1"
0.018559 2.774132 "2x2"
0.026642 1.382778 "3x3"
0.037907 0.885833 "4x4"
0.051000 0.598594 "5x5"
0.068425 0.454618 "6x6"
0.113151 0.279097 "8x8"
EOD
$d2_uniform << EOD
0.004442 14.657407 "1x1"
0.017700 6.748472 "2x2"
0.038851 4.421852 "3x3"
0.068329 3.264907 "4x4"
0.107177 2.674074 "5x5"
0.152481 2.245856 "6x6"
EOD
$d2_stratified << EOD
0.004984 14.505000 "1x1"
0.021430 5.650532 "2x2"
0.044355 3.418426 "3x3"
0.075894 2.274190 "4x4"
0.117313 1.876481 "5x5"
0.175118 1.574977 "6x6"
EOD
$d2_adaptive << EOD
0.035440 3.454815 "a3 t2"
0.035918 3.503565 "a3 t8"
0.056549 2.378542 "a4 t8"
0.057187 2.325440 "a4 t2"
0.082778 1.992384 "a5 t8"
0.094709 1.938056 "a5 t2"
0.117282 1.640856 "a6 t2"
0.118145 1.700995 "a6 t8"
0.148083 1.467245 "a7 t8"
0.153954 1.403102 "a7 t2"
0.239289 1.173773 "a9 t8"
0.248024 1.106898 "a9 t2"
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
