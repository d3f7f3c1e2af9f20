$d0_uniform << EOD
0.046421 3.570868 "1x1"
0.057008 1.734566 "2x2"
0.061334 1.152917 "3x3"
0.078533 0.866563 "4x4"
0.097709 0.687951 "5x5"
0.135028 0.566753 "6x6"
0.209410 0.432135 "8x8"
EOD
$d0_stratified << EOD
0.043915 3.570868 "1x1"
0.051288 0.592969 "2x2"
0.081646 0.236944 "3x3"
0.086554 0.119427 "4x4"
0.124577 0.085087 "5x5"
0.155625 0.058212 "6x6"
0.247625 0.035312 "8x8"
EOD
$d0_adaptive << EOD
0.031315 3.570868 "1x1"
0.051087 0.236944 "3x3"
0.055932 0.592969 "2x2"
0.062559 0.119427 "4x4"
0.084561 0.085087 "5x5"
0.092502 0.058212 "6x6"
0.096685 0.035330 "8x8"
EOD
$d1_uniform << EOD
0.005055 9.048542 "1x1"
0.009885 4.447604 "2x2"
0.017358 2.985191 "3x3"
0.027914 2.261285 "4x4"
0.042650 1.770052 "5x5"
0.045721 1.472222 "6x6"
0.077511 1.145000 "8x8"
EOD
$d1_stratified << EOD
0.004755 9.048542 "1x1"
0.013242 2.125556 "2x2"
0.020298 1.032309 "3x3"
0.028202 0.603750 "4x4"
0.042975 0.434514 "5x5"
0.048653 0.316858 "6x6"
0.109162 0.205451 "8x8"
EOD
$d1_adaptive << EOD
0.005402 9.048542 "1x1"
0.012663 2.120816 "2x2"
0.018653 1.030382 "3x3"
0.025467 0.604271 "4x4"
0.038357 0.435764 "5x5"
0.044868 0.318941 "6x6"
0.070648 0.208941 "8x8"
EOD
$d2_uniform << EOD
0.004370 14.657407 "1x1"
0.017001 6.748472 "2x2"
0.037456 4.421852 "3x3"
0.064821 3.264907 "4x4"
0.093645 2.674074 "5x5"
0.150608 2.245856 "6x6"
EOD
$d2_stratified << EOD
0.003969 14.505000 "1x1"
0.018031 5.650532 "2x2"
0.044681 3.418426 "3x3"
0.075935 2.274190 "4x4"
0.099439 1.876481 "5x5"
0.163721 1.574977 "6x6"
EOD
$d2_adaptive << EOD
0.033645 3.503565 "a3 t8"
0.035031 3.454815 "a3 t2"
0.056267 2.378542 "a4 t8"
0.057951 2.325440 "a4 t2"
0.077417 1.938056 "a5 t2"
0.080905 1.992384 "a5 t8"
0.108036 1.700995 "a6 t8"
0.118842 1.640856 "a6 t2"
0.141983 1.403102 "a7 t2"
0.146067 1.467245 "a7 t8"
0.222007 1.173773 "a9 t8"
0.224852 1.106898 "a9 t2"
EOD
set terminal pngcairo size 1800,600 font 'sans,11' background rgb 'white'
set output '/tmp/soft/q-final/soft.png.tmp'
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
