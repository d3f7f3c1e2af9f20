$d0_depth << EOD
0.030524 10.883981
0.043979 2.518781
0.050093 0.477171
0.055603 0.140550
0.057884 0.093606
0.060236 0.081097
EOD
$d0_full << EOD
0.228120 0.091149
0.503960 0.079099
1.091704 0.074694
1.675050 0.071667
2.456520 0.070272
3.463048 0.069190
4.187632 0.068579
1.149291 0.012053
EOD
$d0_adaptive << EOD
0.190997 0.079834
0.163036 0.080716
0.116979 0.082750
0.092190 0.086667
0.076916 0.100926
0.278826 0.072475
0.295817 0.073431
0.256503 0.075697
0.192595 0.079996
0.129163 0.096025
0.578253 0.070011
0.358242 0.070987
0.307375 0.073334
0.213386 0.077750
0.118978 0.094426
0.341178 0.010817
0.570852 0.008057
EOD
$d0_subsample << EOD
0.048551 10.883981
0.062061 2.518781
0.056487 0.477171
0.057125 0.140550
0.064553 0.093606
0.061301 0.081097
EOD
$p0 << EOD
0.030524 10.883981 "1x1 d0"
0.043979 2.518781 "1x1 d1"
0.050093 0.477171 "1x1 d2"
0.055603 0.140550 "1x1 d3"
0.057884 0.093606 "1x1 d4"
0.060236 0.081097 "1x1 d5"
0.163036 0.080716 "a3 t3 d3"
0.190997 0.079834 "a3 t2 d3"
0.213386 0.077750 "a7 t8 d3"
0.256503 0.075697 "a5 t4 d3"
0.278826 0.072475 "a5 t2 d3"
0.341178 0.010817 "a5 t2 d5"
0.570852 0.008057 "a7 t2 d5"
EOD
$d1_depth << EOD
0.043982 16.152594
0.066200 2.671032
0.074083 0.374081
0.077858 0.132301
0.079538 0.089723
0.079938 0.078123
EOD
$d1_full << EOD
0.312734 0.084356
0.662243 0.072601
1.152085 0.067519
1.595580 0.064832
2.146805 0.063002
3.320974 0.062006
4.057544 0.061218
1.151385 0.012272
EOD
$d1_adaptive << EOD
0.167573 0.073106
0.111771 0.073620
0.107925 0.074604
0.094020 0.077393
0.076477 0.089687
0.218338 0.065360
0.181357 0.065904
0.158566 0.066958
0.168779 0.070004
0.089804 0.084289
0.347940 0.062553
0.277083 0.063106
0.261570 0.064210
0.246284 0.067350
0.111242 0.082295
0.276572 0.010698
0.409759 0.007777
EOD
$d1_subsample << EOD
0.038959 16.152594
0.059448 2.671032
0.061133 0.374081
0.063052 0.132301
0.071247 0.089723
0.072329 0.078123
EOD
$p1 << EOD
0.038959 16.152594 "sub d0"
0.059448 2.671032 "sub d1"
0.061133 0.374081 "sub d2"
0.063052 0.132301 "sub d3"
0.071247 0.089723 "sub d4"
0.072329 0.078123 "sub d5"
0.094020 0.077393 "a3 t8 d3"
0.107925 0.074604 "a3 t4 d3"
0.111771 0.073620 "a3 t3 d3"
0.158566 0.066958 "a5 t4 d3"
0.181357 0.065904 "a5 t3 d3"
0.218338 0.065360 "a5 t2 d3"
0.261570 0.064210 "a7 t4 d3"
0.276572 0.010698 "a5 t2 d5"
0.409759 0.007777 "a7 t2 d5"
EOD
$d2_depth << EOD
0.089022 21.111013
0.124796 2.205091
0.162857 1.520434
0.166852 1.466096
0.184468 1.463877
0.188526 1.463650
EOD
$d2_full << EOD
0.725968 0.535075
1.591354 0.291437
2.821310 0.188791
3.178615 0.137809
5.400695 0.104666
7.864709 0.084284
9.674794 0.070662
2.467595 0.185538
EOD
$d2_adaptive << EOD
1.043426 0.294510
0.939743 0.297716
1.011729 0.299597
0.972485 0.313146
0.600738 0.445947
2.999258 0.141337
3.100576 0.144848
2.975746 0.146871
2.545214 0.162514
1.465860 0.312533
6.294085 0.087924
5.721248 0.091543
5.735185 0.093632
4.411810 0.109865
2.170929 0.265523
3.049745 0.138086
6.209096 0.083887
EOD
$d2_subsample << EOD
0.059499 21.111200
0.105497 2.205098
0.133648 1.520517
0.167822 1.466186
0.175677 1.463964
0.197677 1.463736
EOD
$p2 << EOD
0.059499 21.111200 "sub d0"
0.089022 21.111013 "1x1 d0"
0.105497 2.205098 "sub d1"
0.124796 2.205091 "1x1 d1"
0.133648 1.520517 "sub d2"
0.162857 1.520434 "1x1 d2"
0.166852 1.466096 "1x1 d3"
0.175677 1.463964 "sub d4"
0.184468 1.463877 "1x1 d4"
0.188526 1.463650 "1x1 d5"
0.600738 0.445947 "a3 t32 d3"
0.939743 0.297716 "a3 t3 d3"
1.043426 0.294510 "a3 t2 d3"
1.591354 0.291437 "3x3 d3"
2.170929 0.265523 "a7 t32 d3"
2.467595 0.185538 "4x4 d5"
2.545214 0.162514 "a5 t8 d3"
2.975746 0.146871 "a5 t4 d3"
2.999258 0.141337 "a5 t2 d3"
3.049745 0.138086 "a5 t2 d5"
3.178615 0.137809 "5x5 d3"
4.411810 0.109865 "a7 t8 d3"
5.400695 0.104666 "6x6 d3"
5.721248 0.091543 "a7 t3 d3"
6.209096 0.083887 "a7 t2 d5"
9.674794 0.070662 "8x8 d3"
EOD
$d3_depth << EOD
0.057278 6.464198
0.056781 0.041014
0.058256 0.040810
0.068532 0.040810
0.059185 0.040810
0.056385 0.040810
EOD
$d3_full << EOD
0.355288 0.014978
0.729207 0.008549
1.242608 0.006112
1.705935 0.004335
2.380447 0.003637
3.718708 0.002801
4.635176 0.002471
0.967399 0.006112
EOD
$d3_adaptive << EOD
0.075579 0.010254
0.093073 0.010254
0.101069 0.010254
0.099111 0.010254
0.071316 0.011228
0.080763 0.006469
0.072192 0.006469
0.077630 0.006469
0.085054 0.006469
0.120884 0.007518
0.134722 0.005059
0.081485 0.005059
0.083733 0.005059
0.082567 0.005059
0.078391 0.006131
0.126455 0.006469
0.128607 0.005059
EOD
$d3_subsample << EOD
0.031391 6.465891
0.039576 0.044273
0.038563 0.044158
0.039429 0.044158
0.041093 0.044158
0.039569 0.044158
EOD
$p3 << EOD
0.031391 6.465891 "sub d0"
0.038563 0.044158 "sub d2"
0.056385 0.040810 "1x1 d5"
0.071316 0.011228 "a3 t32 d2"
0.072192 0.006469 "a5 t3 d2"
0.078391 0.006131 "a7 t32 d2"
0.081485 0.005059 "a7 t3 d2"
1.705935 0.004335 "5x5 d2"
2.380447 0.003637 "6x6 d2"
3.718708 0.002801 "7x7 d2"
4.635176 0.002471 "8x8 d2"
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
