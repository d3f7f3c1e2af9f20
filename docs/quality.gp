$d0_depth << EOD
0.010345 10.939626
0.016639 2.577000
0.021906 0.547144
0.021465 0.218941
0.020001 0.174804
0.021473 0.163285
EOD
$d0_full << EOD
0.080561 0.114452
0.148750 0.091074
0.272415 0.082644
0.446835 0.077615
0.657683 0.074470
0.868139 0.072281
1.194391 0.071874
0.333470 0.021493
EOD
$d0_adaptive << EOD
0.068997 0.091959
0.063633 0.093400
0.053958 0.096596
0.042184 0.104581
0.030627 0.135552
0.157619 0.078615
0.120016 0.080174
0.098100 0.083763
0.056880 0.092415
0.034945 0.126015
0.265515 0.073285
0.232830 0.074937
0.203204 0.078656
0.135991 0.087674
0.065588 0.122944
0.171695 0.018478
0.314616 0.012511
EOD
$d0_subsample << EOD
0.010273 10.939626
0.016875 2.577000
0.020209 0.547144
0.021467 0.218941
0.022734 0.174804
0.023491 0.163285
EOD
$p0 << EOD
0.010273 10.939626 "sub d0"
0.016639 2.577000 "1x1 d1"
0.020001 0.174804 "1x1 d4"
0.021473 0.163285 "1x1 d5"
0.030627 0.135552 "a3 t32 d3"
0.034945 0.126015 "a5 t32 d3"
0.042184 0.104581 "a3 t8 d3"
0.053958 0.096596 "a3 t4 d3"
0.056880 0.092415 "a5 t8 d3"
0.068997 0.091959 "a3 t2 d3"
0.098100 0.083763 "a5 t4 d3"
0.120016 0.080174 "a5 t3 d3"
0.157619 0.078615 "a5 t2 d3"
0.171695 0.018478 "a5 t2 d5"
0.314616 0.012511 "a7 t2 d5"
EOD
$d1_depth << EOD
0.010997 16.231256
0.017050 2.723722
0.019403 0.449904
0.020428 0.210022
0.021332 0.168633
0.022010 0.157259
EOD
$d1_full << EOD
0.080774 0.109226
0.170724 0.086978
0.246114 0.075978
0.415679 0.071141
0.692419 0.068115
0.929092 0.065774
1.245275 0.064530
0.328916 0.021574
EOD
$d1_adaptive << EOD
0.060312 0.087659
0.052227 0.088426
0.048231 0.090144
0.038731 0.095941
0.029359 0.122285
0.151695 0.071830
0.111840 0.072637
0.090371 0.074481
0.064592 0.080848
0.038918 0.110600
0.234970 0.066485
0.187125 0.067341
0.155035 0.069274
0.112023 0.075833
0.052689 0.106837
0.127491 0.017941
0.236329 0.012430
EOD
$d1_subsample << EOD
0.011089 16.231256
0.017496 2.723722
0.019939 0.449904
0.021007 0.210022
0.022003 0.168633
0.022869 0.157259
EOD
$p1 << EOD
0.010997 16.231256 "1x1 d0"
0.017050 2.723722 "1x1 d1"
0.019403 0.449904 "1x1 d2"
0.020428 0.210022 "1x1 d3"
0.021332 0.168633 "1x1 d4"
0.022010 0.157259 "1x1 d5"
0.029359 0.122285 "a3 t32 d3"
0.038731 0.095941 "a3 t8 d3"
0.048231 0.090144 "a3 t4 d3"
0.052227 0.088426 "a3 t3 d3"
0.060312 0.087659 "a3 t2 d3"
0.064592 0.080848 "a5 t8 d3"
0.090371 0.074481 "a5 t4 d3"
0.111840 0.072637 "a5 t3 d3"
0.127491 0.017941 "a5 t2 d5"
0.236329 0.012430 "a7 t2 d5"
EOD
$d2_depth << EOD
0.135604 21.722909
0.154939 3.236929
0.183736 2.669321
0.183314 2.623241
0.196438 2.622677
0.200040 2.622353
EOD
$d2_full << EOD
0.708782 0.955648
1.626953 0.518465
2.690244 0.333573
4.055810 0.237122
6.245529 0.183318
8.567695 0.145849
10.892722 0.125579
3.162165 0.332477
EOD
$d2_adaptive << EOD
1.166458 0.519884
1.140965 0.522454
0.945985 0.524290
1.002363 0.530532
0.757944 0.676921
2.836992 0.238773
2.748947 0.241582
2.691547 0.243642
2.499878 0.250841
1.809737 0.420177
5.356227 0.147616
5.210353 0.150502
5.053583 0.152662
5.418302 0.160131
3.599327 0.336042
3.124755 0.237515
6.046808 0.145386
EOD
$d2_subsample << EOD
0.084305 21.724066
0.145556 3.237693
0.149733 2.669985
0.169327 2.623951
0.160259 2.623380
0.170790 2.623056
EOD
$p2 << EOD
0.084305 21.724066 "sub d0"
0.135604 21.722909 "1x1 d0"
0.145556 3.237693 "sub d1"
0.149733 2.669985 "sub d2"
0.160259 2.623380 "sub d4"
0.170790 2.623056 "sub d5"
0.196438 2.622677 "1x1 d4"
0.200040 2.622353 "1x1 d5"
0.708782 0.955648 "2x2 d3"
0.757944 0.676921 "a3 t32 d3"
0.945985 0.524290 "a3 t4 d3"
1.140965 0.522454 "a3 t3 d3"
1.166458 0.519884 "a3 t2 d3"
1.626953 0.518465 "3x3 d3"
1.809737 0.420177 "a5 t32 d3"
2.499878 0.250841 "a5 t8 d3"
2.691547 0.243642 "a5 t4 d3"
2.748947 0.241582 "a5 t3 d3"
2.836992 0.238773 "a5 t2 d3"
3.124755 0.237515 "a5 t2 d5"
4.055810 0.237122 "5x5 d3"
5.053583 0.152662 "a7 t4 d3"
5.210353 0.150502 "a7 t3 d3"
5.356227 0.147616 "a7 t2 d3"
6.046808 0.145386 "a7 t2 d5"
10.892722 0.125579 "8x8 d3"
EOD
$d3_depth << EOD
0.037053 6.514541
0.048555 0.078233
0.047668 0.077974
0.046557 0.077974
0.046832 0.077974
0.046787 0.077974
EOD
$d3_full << EOD
0.185592 0.030333
0.417666 0.018089
0.751663 0.012552
1.192094 0.009248
1.692172 0.007526
2.304942 0.006381
2.994844 0.005133
0.692780 0.012552
EOD
$d3_adaptive << EOD
0.057367 0.026667
0.059104 0.026667
0.053366 0.026667
0.053402 0.026667
0.052958 0.027915
0.059531 0.020244
0.060829 0.020244
0.059623 0.020244
0.057317 0.020244
0.061037 0.021507
0.071708 0.018126
0.071836 0.018126
0.071504 0.018126
0.072460 0.018126
0.068994 0.019422
0.062346 0.020244
0.073211 0.018126
EOD
$d3_subsample << EOD
0.022147 6.509456
0.028357 0.075885
0.025100 0.075730
0.022472 0.075730
0.032462 0.075730
0.032482 0.075730
EOD
$p3 << EOD
0.022147 6.509456 "sub d0"
0.022472 0.075730 "sub d3"
0.052958 0.027915 "a3 t32 d2"
0.053366 0.026667 "a3 t4 d2"
0.057317 0.020244 "a5 t8 d2"
0.068994 0.019422 "a7 t32 d2"
0.071504 0.018126 "a7 t4 d2"
0.417666 0.018089 "3x3 d2"
0.692780 0.012552 "4x4 d5"
1.192094 0.009248 "5x5 d2"
1.692172 0.007526 "6x6 d2"
2.304942 0.006381 "7x7 d2"
2.994844 0.005133 "8x8 d2"
EOD
set terminal pngcairo size 1600,1200 font 'sans,11' background rgb 'white'
set output 'docs/quality.png.tmp'
set multiplot layout 2,2 title 'raytrace: run time against error (median CPU time of >= 5 runs, 1 process; error against 16x16 samples, depth 10)'
set logscale xy
set grid
set xlabel 'CPU time (s)'
set ylabel 'mean absolute error (0-255 per channel)'
set key top right font ',10'
set title 'cgfs (300x300)'
plot $d0_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d0_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d0_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d0_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p0 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p0 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p0 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'cgfs-camera (300x300)'
plot $d1_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d1_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d1_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d1_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p1 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p1 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p1 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'sphere-grid (240x180)'
plot $d2_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d2_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d2_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d2_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p2 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p2 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p2 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'tiny-spheres (300x300)'
plot $d3_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d3_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d3_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d3_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p3 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p3 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p3 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
unset multiplot
