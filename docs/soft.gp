$d0_uniform << EOD
0.036928 3.570868 "1x1"
0.047038 1.734566 "2x2"
0.063504 1.152917 "3x3"
0.084695 0.866563 "4x4"
0.112766 0.687951 "5x5"
0.146413 0.566753 "6x6"
0.231307 0.432135 "8x8"
EOD
$d0_stratified << EOD
0.029688 3.570868 "1x1"
0.041869 0.592969 "2x2"
0.053967 0.236944 "3x3"
0.056985 0.119427 "4x4"
0.068670 0.085087 "5x5"
0.081568 0.058212 "6x6"
0.092894 0.035312 "8x8"
EOD
$d0_adaptive << EOD
0.033836 0.592969 "2x2"
0.034073 3.570868 "1x1"
0.040013 0.236944 "3x3"
0.056416 0.119427 "4x4"
0.066328 0.085087 "5x5"
0.083410 0.058212 "6x6"
0.116274 0.035330 "8x8"
EOD
$d1_uniform << EOD
0.003423 9.048542 "1x1"
0.006875 4.447604 "2x2"
0.018508 2.985191 "3x3"
0.029917 2.261285 "4x4"
0.044112 1.770052 "5x5"
0.059720 1.472222 "6x6"
0.103779 1.145000 "8x8"
EOD
$d1_stratified << EOD
0.005646 9.048542 "1x1"
0.014678 2.125556 "2x2"
0.022166 1.032309 "3x3"
0.026392 0.603750 "4x4"
0.040610 0.434514 "5x5"
0.052050 0.316858 "6x6"
0.082182 0.205451 "8x8"
EOD
$d1_adaptive << EOD
0.005458 9.048542 "1x1"
0.011451 2.120816 "2x2"
0.018233 1.030382 "3x3"
0.023924 0.604271 "4x4"
0.035708 0.435764 "5x5"
0.046591 0.318941 "6x6"
0.071179 0.208941 "8x8"
EOD
$d2_uniform << EOD
0.004414 14.657407 "1x1"
0.017618 6.748472 "2x2"
0.039084 4.421852 "3x3"
0.069239 3.264907 "4x4"
0.108765 2.674074 "5x5"
0.154311 2.245856 "6x6"
EOD
$d2_stratified << EOD
0.004900 14.505000 "1x1"
0.021293 5.650532 "2x2"
0.045150 3.418426 "3x3"
0.079558 2.274190 "4x4"
0.137949 1.876481 "5x5"
0.149059 1.574977 "6x6"
EOD
$d2_adaptive << EOD
0.025809 3.454815 "a3 t2"
0.034582 3.503565 "a3 t8"
0.048967 2.325440 "a4 t2"
0.051821 2.378542 "a4 t8"
0.061877 1.992384 "a5 t8"
0.063709 1.938056 "a5 t2"
0.098703 1.700995 "a6 t8"
0.113622 1.640856 "a6 t2"
0.121646 1.467245 "a7 t8"
0.127194 1.403102 "a7 t2"
0.198799 1.173773 "a9 t8"
0.249720 1.106898 "a9 t2"
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
