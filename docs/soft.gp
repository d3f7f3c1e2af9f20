$d0_uniform << EOD
0.025953 3.570868 "1x1"
0.044428 1.734566 "2x2"
0.046162 1.152917 "3x3"
0.060094 0.866563 "4x4"
0.076570 0.687951 "5x5"
0.104707 0.566753 "6x6"
0.172674 0.432135 "8x8"
EOD
$d0_stratified << EOD
0.030374 3.570868 "1x1"
0.036111 0.592969 "2x2"
0.049212 0.236944 "3x3"
0.055753 0.119427 "4x4"
0.057614 0.085087 "5x5"
0.086462 0.058212 "6x6"
0.099079 0.035312 "8x8"
EOD
$d0_adaptive << EOD
0.029509 3.570868 "1x1"
0.032640 0.592969 "2x2"
0.039575 0.236944 "3x3"
0.048274 0.119427 "4x4"
0.067299 0.085087 "5x5"
0.083100 0.058212 "6x6"
0.095622 0.035330 "8x8"
EOD
$d1_uniform << EOD
0.003800 9.048542 "1x1"
0.007480 4.447604 "2x2"
0.013574 2.985191 "3x3"
0.021493 2.261285 "4x4"
0.031571 1.770052 "5x5"
0.059811 1.472222 "6x6"
0.105674 1.145000 "8x8"
EOD
$d1_stratified << EOD
0.005461 9.048542 "1x1"
0.012410 2.125556 "2x2"
0.018033 1.032309 "3x3"
0.021438 0.603750 "4x4"
0.038466 0.434514 "5x5"
0.050212 0.316858 "6x6"
0.076398 0.205451 "8x8"
EOD
$d1_adaptive << EOD
0.005021 9.048542 "1x1"
0.011306 2.120816 "2x2"
0.016671 1.030382 "3x3"
0.022953 0.604271 "4x4"
0.034154 0.435764 "5x5"
0.044386 0.318941 "6x6"
0.067615 0.208941 "8x8"
EOD
$d2_uniform << EOD
0.004343 14.657407 "1x1"
0.014022 6.748472 "2x2"
0.036758 4.421852 "3x3"
0.067369 3.264907 "4x4"
0.104913 2.674074 "5x5"
0.152005 2.245856 "6x6"
EOD
$d2_stratified << EOD
0.003785 14.505000 "1x1"
0.021028 5.650532 "2x2"
0.044132 3.418426 "3x3"
0.077389 2.274190 "4x4"
0.121355 1.876481 "5x5"
0.177440 1.574977 "6x6"
EOD
$d2_adaptive << EOD
0.027293 3.503565 "a3 t8"
0.033826 3.454815 "a3 t2"
0.054619 2.378542 "a4 t8"
0.056027 2.325440 "a4 t2"
0.069548 1.938056 "a5 t2"
0.075919 1.992384 "a5 t8"
0.109669 1.700995 "a6 t8"
0.109684 1.640856 "a6 t2"
0.123495 1.403102 "a7 t2"
0.137634 1.467245 "a7 t8"
0.204291 1.106898 "a9 t2"
0.204841 1.173773 "a9 t8"
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
