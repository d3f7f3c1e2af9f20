$d0_depth << EOD
0.019079 8.415803
0.022863 6.956975
0.026631 4.064753
0.036185 3.848355
0.034893 3.835864
0.038581 3.835525
0.051455 3.835443
0.067088 3.835464
EOD
$d0_full << EOD
0.175178 1.570872
0.611602 1.225464
0.949186 0.656359
1.158454 0.566432
1.575796 0.393060
2.110687 0.411662
2.743786 0.382296
EOD
$d0_adaptive << EOD
0.240332 1.297465
0.230640 1.301615
0.214451 1.305933
0.171081 1.326233
0.141586 1.362448
0.637694 0.662322
0.644536 0.667179
0.559473 0.672391
0.742564 0.695256
0.435242 0.736003
1.189024 0.516246
1.476561 0.521424
1.363794 0.526901
0.861751 0.550764
0.606031 0.593281
EOD
$d0_subsample << EOD
0.029881 8.415803
0.040026 6.956975
0.045932 4.064753
0.051557 3.848355
0.058261 3.835864
0.063319 3.835525
EOD
$p0 << EOD
0.019079 8.415803 "1x1 d0"
0.022863 6.956975 "1x1 d1"
0.026631 4.064753 "1x1 d2"
0.034893 3.835864 "1x1 d4"
0.038581 3.835525 "1x1 d5"
0.051455 3.835443 "1x1 d6"
0.141586 1.362448 "a3 t32 d6"
0.171081 1.326233 "a3 t8 d6"
0.214451 1.305933 "a3 t4 d6"
0.230640 1.301615 "a3 t3 d6"
0.240332 1.297465 "a3 t2 d6"
0.435242 0.736003 "a5 t32 d6"
0.559473 0.672391 "a5 t4 d6"
0.606031 0.593281 "a7 t32 d6"
0.861751 0.550764 "a7 t8 d6"
1.189024 0.516246 "a7 t2 d6"
1.575796 0.393060 "6x6 d6"
2.743786 0.382296 "8x8 d6"
EOD
$d1_depth << EOD
0.012976 7.327122
0.015216 6.513218
0.018694 4.990532
0.021029 5.003449
0.023664 4.985548
0.025692 4.976265
0.028542 4.975147
0.031734 4.974468
EOD
$d1_full << EOD
0.110787 2.330532
0.251513 1.351991
0.484603 1.086227
0.713847 0.670818
1.676845 0.790525
1.498248 0.692022
1.946107 0.355988
EOD
$d1_adaptive << EOD
0.254968 1.463503
0.277129 1.495625
0.251455 1.503110
0.091757 1.526343
0.089829 1.529691
0.431837 0.806512
0.426722 0.842623
0.379147 0.851073
0.214691 0.877531
0.210725 0.881142
0.927576 0.823318
0.816476 0.858025
0.725787 0.867045
0.405119 0.894691
0.379482 0.898233
EOD
$d1_subsample << EOD
0.011091 7.327122
0.013523 6.513218
0.015933 4.990532
0.018124 5.003449
0.020343 4.985548
0.023090 4.976265
EOD
$p1 << EOD
0.011091 7.327122 "sub d0"
0.013523 6.513218 "sub d1"
0.015933 4.990532 "sub d2"
0.020343 4.985548 "sub d4"
0.023090 4.976265 "sub d5"
0.028542 4.975147 "1x1 d6"
0.031734 4.974468 "1x1 d8"
0.089829 1.529691 "a3 t32 d6"
0.091757 1.526343 "a3 t8 d6"
0.210725 0.881142 "a5 t32 d6"
0.214691 0.877531 "a5 t8 d6"
0.379147 0.851073 "a5 t4 d6"
0.426722 0.842623 "a5 t3 d6"
0.431837 0.806512 "a5 t2 d6"
0.713847 0.670818 "5x5 d6"
1.946107 0.355988 "8x8 d6"
EOD
$d2_depth << EOD
0.018566 0.421592
0.018054 0.421592
0.018067 0.421592
0.018233 0.421592
0.018185 0.421592
0.018026 0.421592
0.017893 0.421592
0.017996 0.421592
EOD
$d2_full << EOD
0.082089 0.143950
0.160443 0.076158
0.280705 0.048733
0.453657 0.031983
0.801460 0.024950
1.250550 0.019875
1.911268 0.015867
0.280184 0.048733
EOD
$d2_adaptive << EOD
0.059782 0.076292
0.047879 0.076617
0.055270 0.076808
0.050051 0.077417
0.053374 0.091617
0.119448 0.032142
0.115298 0.032458
0.085648 0.032675
0.053992 0.033283
0.076470 0.049483
0.130616 0.020033
0.124185 0.020375
0.119279 0.020592
0.128411 0.021208
0.074952 0.038058
0.063553 0.032142
0.106212 0.020033
EOD
$d2_subsample << EOD
0.017858 0.421592
0.017618 0.421592
0.017586 0.421592
0.017483 0.421592
0.017322 0.421592
0.030489 0.421592
EOD
$p2 << EOD
0.017322 0.421592 "sub d4"
0.047879 0.076617 "a3 t3 d3"
0.053992 0.033283 "a5 t8 d3"
0.063553 0.032142 "a5 t2 d5"
0.106212 0.020033 "a7 t2 d5"
1.250550 0.019875 "7x7 d3"
1.911268 0.015867 "8x8 d3"
EOD
set terminal pngcairo size 1800,560 font 'sans,11' background rgb 'white'
set output 'docs/quality-glass.png.tmp'
set multiplot layout 1,3 title 'raytrace: run time against error (median CPU time of >= 3 runs, 1 process; error against 16x16 samples, depth 10)'
set logscale xy
set grid
set xlabel 'CPU time (s)'
set ylabel 'mean absolute error (0-255 per channel)'
set key top right font ',10'
set title 'glass (320x240)'
plot $d0_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-6 and 8, 1 ray per pixel', \
  $d0_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d0_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d0_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p0 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p0 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p0 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'glass-lens (240x180)'
plot $d1_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-6 and 8, 1 ray per pixel', \
  $d1_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d1_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d1_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p1 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p1 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p1 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'die (200x200)'
plot $d2_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-6 and 8, 1 ray per pixel', \
  $d2_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d2_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d2_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p2 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p2 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p2 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
unset multiplot
