$d0_depth << EOD
0.044300 10.883981
0.069103 2.518781
0.081235 0.477171
0.082390 0.140550
0.073984 0.093606
0.074033 0.081097
EOD
$d0_full << EOD
0.296869 0.091149
0.662920 0.079099
1.188494 0.074694
1.849652 0.071667
2.704888 0.070272
3.731626 0.069190
4.599615 0.068579
1.194328 0.012053
EOD
$d0_adaptive << EOD
0.142790 0.079834
0.179067 0.080716
0.116830 0.082750
0.111752 0.086667
0.088272 0.100926
0.303490 0.072475
0.311785 0.073431
0.258272 0.075697
0.190870 0.079996
0.129990 0.096025
0.573961 0.070011
0.454106 0.070987
0.386840 0.073334
0.231697 0.077750
0.124413 0.094426
0.290444 0.010817
0.625953 0.008057
EOD
$d0_subsample << EOD
0.037089 10.883981
0.063264 2.518781
0.074047 0.477171
0.078476 0.140550
0.079453 0.093606
0.083185 0.081097
EOD
$p0 << EOD
0.037089 10.883981 "sub d0"
0.063264 2.518781 "sub d1"
0.073984 0.093606 "1x1 d4"
0.074033 0.081097 "1x1 d5"
0.142790 0.079834 "a3 t2 d3"
0.231697 0.077750 "a7 t8 d3"
0.258272 0.075697 "a5 t4 d3"
0.290444 0.010817 "a5 t2 d5"
0.625953 0.008057 "a7 t2 d5"
EOD
$d1_depth << EOD
0.048863 16.152594
0.072580 2.671032
0.080776 0.374081
0.083395 0.132301
0.080791 0.089723
0.082496 0.078123
EOD
$d1_full << EOD
0.282316 0.084356
0.577167 0.072601
1.068756 0.067519
1.800271 0.064832
2.270801 0.063002
3.562903 0.062006
4.780649 0.061218
1.277311 0.012272
EOD
$d1_adaptive << EOD
0.171992 0.073106
0.150390 0.073620
0.129399 0.074604
0.124454 0.077393
0.105189 0.089687
0.354745 0.065360
0.310704 0.065904
0.206436 0.066958
0.178438 0.070004
0.125091 0.084289
0.491692 0.062553
0.408658 0.063106
0.328737 0.064210
0.234056 0.067350
0.159455 0.082295
0.292375 0.010698
0.466984 0.007777
EOD
$d1_subsample << EOD
0.048089 16.152594
0.071047 2.671032
0.078444 0.374081
0.081615 0.132301
0.084458 0.089723
0.084497 0.078123
EOD
$p1 << EOD
0.048089 16.152594 "sub d0"
0.071047 2.671032 "sub d1"
0.078444 0.374081 "sub d2"
0.080791 0.089723 "1x1 d4"
0.082496 0.078123 "1x1 d5"
0.124454 0.077393 "a3 t8 d3"
0.129399 0.074604 "a3 t4 d3"
0.150390 0.073620 "a3 t3 d3"
0.171992 0.073106 "a3 t2 d3"
0.178438 0.070004 "a5 t8 d3"
0.206436 0.066958 "a5 t4 d3"
0.292375 0.010698 "a5 t2 d5"
0.466984 0.007777 "a7 t2 d5"
EOD
$d2_depth << EOD
0.085147 21.111013
0.119945 2.205091
0.177282 1.520434
0.202689 1.466096
0.209798 1.463877
0.202046 1.463650
EOD
$d2_full << EOD
0.751350 0.535075
1.599611 0.291437
2.237017 0.188791
3.470925 0.137809
5.153411 0.104666
6.634520 0.084284
8.431796 0.070662
3.236140 0.185538
EOD
$d2_adaptive << EOD
1.001938 0.294510
1.075401 0.297716
0.886822 0.299597
1.060593 0.313146
0.651419 0.445947
3.304240 0.141337
2.860439 0.144848
2.781158 0.146871
2.518516 0.162514
1.484090 0.312533
5.836564 0.087924
5.617144 0.091543
5.189478 0.093632
4.230889 0.109865
2.745238 0.265523
3.645829 0.138086
6.562688 0.083887
EOD
$d2_subsample << EOD
0.069187 21.111200
0.117838 2.205098
0.133744 1.520517
0.169560 1.466186
0.189510 1.463964
0.182599 1.463736
EOD
$p2 << EOD
0.069187 21.111200 "sub d0"
0.085147 21.111013 "1x1 d0"
0.117838 2.205098 "sub d1"
0.119945 2.205091 "1x1 d1"
0.133744 1.520517 "sub d2"
0.169560 1.466186 "sub d3"
0.182599 1.463736 "sub d5"
0.202046 1.463650 "1x1 d5"
0.651419 0.445947 "a3 t32 d3"
0.886822 0.299597 "a3 t4 d3"
1.001938 0.294510 "a3 t2 d3"
1.599611 0.291437 "3x3 d3"
2.237017 0.188791 "4x4 d3"
2.518516 0.162514 "a5 t8 d3"
2.781158 0.146871 "a5 t4 d3"
2.860439 0.144848 "a5 t3 d3"
3.304240 0.141337 "a5 t2 d3"
3.470925 0.137809 "5x5 d3"
4.230889 0.109865 "a7 t8 d3"
5.153411 0.104666 "6x6 d3"
5.189478 0.093632 "a7 t4 d3"
5.617144 0.091543 "a7 t3 d3"
5.836564 0.087924 "a7 t2 d3"
6.562688 0.083887 "a7 t2 d5"
8.431796 0.070662 "8x8 d3"
EOD
$d3_depth << EOD
0.071551 6.464198
0.082978 0.041014
0.093497 0.040810
0.088295 0.040810
0.064983 0.040810
0.092191 0.040810
EOD
$d3_full << EOD
0.278536 0.014978
0.686913 0.008549
1.154099 0.006112
1.496096 0.004335
2.374389 0.003637
2.982101 0.002801
4.721912 0.002471
1.172872 0.006112
EOD
$d3_adaptive << EOD
0.094925 0.010254
0.076849 0.010254
0.090379 0.010254
0.069529 0.010254
0.071988 0.011228
0.078302 0.006469
0.078719 0.006469
0.082426 0.006469
0.073816 0.006469
0.114740 0.007518
0.123977 0.005059
0.129575 0.005059
0.121739 0.005059
0.123572 0.005059
0.122956 0.006131
0.119392 0.006469
0.121223 0.005059
EOD
$d3_subsample << EOD
0.035375 6.465891
0.054197 0.044273
0.054213 0.044158
0.056781 0.044158
0.046109 0.044158
0.059640 0.044158
EOD
$p3 << EOD
0.035375 6.465891 "sub d0"
0.046109 0.044158 "sub d4"
0.064983 0.040810 "1x1 d4"
0.069529 0.010254 "a3 t8 d2"
0.073816 0.006469 "a5 t8 d2"
0.121223 0.005059 "a7 t2 d5"
1.496096 0.004335 "5x5 d2"
2.374389 0.003637 "6x6 d2"
2.982101 0.002801 "7x7 d2"
4.721912 0.002471 "8x8 d2"
EOD
set terminal pngcairo size 1600,1200 font 'sans,11' background rgb 'white'
set output 'docs/quality.png.tmp'
set multiplot layout 2,2 title 'raytrace: run time against error (median CPU time of >= 5 runs, 1 process; error against 16x16 samples, depth 10)'
set logscale xy
set grid
set xlabel 'CPU time (s)'
set ylabel 'mean absolute error (0-255 per channel)'
set key top right font ',10'
set title 'cgfs (600x600)'
plot $d0_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d0_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d0_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d0_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p0 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p0 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p0 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'cgfs-camera (600x600)'
plot $d1_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d1_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d1_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d1_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p1 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p1 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p1 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'sphere-grid (480x360)'
plot $d2_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d2_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d2_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d2_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p2 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p2 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p2 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
set title 'tiny-spheres (600x600)'
plot $d3_depth using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'depth 0-5, 1 ray per pixel', \
  $d3_full using 1:2 with points pt 5 ps 1.2 lc rgb '#2ca02c' title 'full N x N, N = 2-8', \
  $d3_adaptive using 1:2 with points pt 9 ps 1.2 lc rgb '#d62728' title 'adaptive (a) N = 3,5,7; t = 2-32', \
  $d3_subsample using 1:2 with points pt 13 ps 1.2 lc rgb '#9467bd' title 'subsampling (sub), depth 0-5', \
  $p3 using 1:2 with steps lw 1.5 lc rgb 'black' title 'Pareto front', \
  $p3 using 1:2 with points pt 6 ps 2 lc rgb 'black' notitle, \
  $p3 using 1:2:3 with labels left offset 0.8,0.6 rotate by 20 font ',8' notitle
unset multiplot
