set terminal pngcairo noenhanced size 1300,1140 font ',10'
set output 'profiles.png'
set multiplot layout 3,2 rowsfirst title 'Dolan–Moré performance and Moré–Wild data profiles'
set key top right font ',8'
set grid
set linetype 1 lc rgb '#000000' lw 1.5
set linetype 2 lc rgb '#E69F00' lw 1.5
set linetype 3 lc rgb '#56B4E9' lw 1.5
set linetype 4 lc rgb '#009E73' lw 1.5
set linetype 5 lc rgb '#0072B2' lw 1.5
set linetype 6 lc rgb '#D55E00' lw 1.5
set linetype 7 lc rgb '#CC79A7' lw 1.5
set linetype 8 lc rgb '#999999' lw 1.5
set linetype 9 lc rgb '#000000' lw 1.5 dt 2
set linetype 10 lc rgb '#E69F00' lw 1.5 dt 2
set linetype 11 lc rgb '#56B4E9' lw 1.5 dt 2
set linetype 12 lc rgb '#009E73' lw 1.5 dt 2
set linetype 13 lc rgb '#0072B2' lw 1.5 dt 2
set linetype 14 lc rgb '#D55E00' lw 1.5 dt 2
set linetype 15 lc rgb '#CC79A7' lw 1.5 dt 2
set linetype 16 lc rgb '#999999' lw 1.5 dt 2
set linetype cycle 16
set title 'performance profile, τ = 0.1'
set xlabel 'α: within α times the best solver''s cost'
set ylabel 'fraction of instances'
unset logscale y
set format y
set logscale x
set format x "%.0e"
set yrange [0:1.02]
plot 'profiles.dat' index 0 with lines lt 1 title 'sdcc/adjoint/grid_max', 'profiles.dat' index 1 with lines lt 2 title 'slsqp/adjoint/grid_max', 'profiles.dat' index 2 with lines lt 3 title 'mma/adjoint/grid_max', 'profiles.dat' index 3 with lines lt 4 title 'ccsaq/adjoint/grid_max', 'profiles.dat' index 4 with lines lt 5 title 'ipopt/adjoint/grid_max', 'profiles.dat' index 5 with lines lt 6 title 'sdcc/adjoint/positive_part', 'profiles.dat' index 6 with lines lt 7 title 'slsqp/adjoint/positive_part', 'profiles.dat' index 7 with lines lt 8 title 'mma/adjoint/positive_part', 'profiles.dat' index 8 with lines lt 9 title 'ccsaq/adjoint/positive_part', 'profiles.dat' index 9 with lines lt 10 title 'ipopt/adjoint/positive_part'
set title 'data profile, τ = 0.1'
set xlabel 'simulation-equivalents'
set ylabel 'fraction of instances'
unset logscale y
set format y
set logscale x
set format x "%.0e"
set yrange [0:1.02]
plot 'profiles.dat' index 10 with lines lt 1 title 'sdcc/adjoint/grid_max', 'profiles.dat' index 11 with lines lt 2 title 'slsqp/adjoint/grid_max', 'profiles.dat' index 12 with lines lt 3 title 'mma/adjoint/grid_max', 'profiles.dat' index 13 with lines lt 4 title 'ccsaq/adjoint/grid_max', 'profiles.dat' index 14 with lines lt 5 title 'ipopt/adjoint/grid_max', 'profiles.dat' index 15 with lines lt 6 title 'sdcc/adjoint/positive_part', 'profiles.dat' index 16 with lines lt 7 title 'slsqp/adjoint/positive_part', 'profiles.dat' index 17 with lines lt 8 title 'mma/adjoint/positive_part', 'profiles.dat' index 18 with lines lt 9 title 'ccsaq/adjoint/positive_part', 'profiles.dat' index 19 with lines lt 10 title 'ipopt/adjoint/positive_part'
set title 'performance profile, τ = 0.001'
set xlabel 'α: within α times the best solver''s cost'
set ylabel 'fraction of instances'
unset logscale y
set format y
set logscale x
set format x "%.0e"
set yrange [0:1.02]
plot 'profiles.dat' index 20 with lines lt 1 title 'sdcc/adjoint/grid_max', 'profiles.dat' index 21 with lines lt 2 title 'slsqp/adjoint/grid_max', 'profiles.dat' index 22 with lines lt 3 title 'mma/adjoint/grid_max', 'profiles.dat' index 23 with lines lt 4 title 'ccsaq/adjoint/grid_max', 'profiles.dat' index 24 with lines lt 5 title 'ipopt/adjoint/grid_max', 'profiles.dat' index 25 with lines lt 6 title 'sdcc/adjoint/positive_part', 'profiles.dat' index 26 with lines lt 7 title 'slsqp/adjoint/positive_part', 'profiles.dat' index 27 with lines lt 8 title 'mma/adjoint/positive_part', 'profiles.dat' index 28 with lines lt 9 title 'ccsaq/adjoint/positive_part', 'profiles.dat' index 29 with lines lt 10 title 'ipopt/adjoint/positive_part'
set title 'data profile, τ = 0.001'
set xlabel 'simulation-equivalents'
set ylabel 'fraction of instances'
unset logscale y
set format y
set logscale x
set format x "%.0e"
set yrange [0:1.02]
plot 'profiles.dat' index 30 with lines lt 1 title 'sdcc/adjoint/grid_max', 'profiles.dat' index 31 with lines lt 2 title 'slsqp/adjoint/grid_max', 'profiles.dat' index 32 with lines lt 3 title 'mma/adjoint/grid_max', 'profiles.dat' index 33 with lines lt 4 title 'ccsaq/adjoint/grid_max', 'profiles.dat' index 34 with lines lt 5 title 'ipopt/adjoint/grid_max', 'profiles.dat' index 35 with lines lt 6 title 'sdcc/adjoint/positive_part', 'profiles.dat' index 36 with lines lt 7 title 'slsqp/adjoint/positive_part', 'profiles.dat' index 37 with lines lt 8 title 'mma/adjoint/positive_part', 'profiles.dat' index 38 with lines lt 9 title 'ccsaq/adjoint/positive_part', 'profiles.dat' index 39 with lines lt 10 title 'ipopt/adjoint/positive_part'
set title 'performance profile, τ = 1e-05'
set xlabel 'α: within α times the best solver''s cost'
set ylabel 'fraction of instances'
unset logscale y
set format y
set logscale x
set format x "%.0e"
set yrange [0:1.02]
plot 'profiles.dat' index 40 with lines lt 1 title 'sdcc/adjoint/grid_max', 'profiles.dat' index 41 with lines lt 2 title 'slsqp/adjoint/grid_max', 'profiles.dat' index 42 with lines lt 3 title 'mma/adjoint/grid_max', 'profiles.dat' index 43 with lines lt 4 title 'ccsaq/adjoint/grid_max', 'profiles.dat' index 44 with lines lt 5 title 'ipopt/adjoint/grid_max', 'profiles.dat' index 45 with lines lt 6 title 'sdcc/adjoint/positive_part', 'profiles.dat' index 46 with lines lt 7 title 'slsqp/adjoint/positive_part', 'profiles.dat' index 47 with lines lt 8 title 'mma/adjoint/positive_part', 'profiles.dat' index 48 with lines lt 9 title 'ccsaq/adjoint/positive_part', 'profiles.dat' index 49 with lines lt 10 title 'ipopt/adjoint/positive_part'
set title 'data profile, τ = 1e-05'
set xlabel 'simulation-equivalents'
set ylabel 'fraction of instances'
unset logscale y
set format y
set logscale x
set format x "%.0e"
set yrange [0:1.02]
plot 'profiles.dat' index 50 with lines lt 1 title 'sdcc/adjoint/grid_max', 'profiles.dat' index 51 with lines lt 2 title 'slsqp/adjoint/grid_max', 'profiles.dat' index 52 with lines lt 3 title 'mma/adjoint/grid_max', 'profiles.dat' index 53 with lines lt 4 title 'ccsaq/adjoint/grid_max', 'profiles.dat' index 54 with lines lt 5 title 'ipopt/adjoint/grid_max', 'profiles.dat' index 55 with lines lt 6 title 'sdcc/adjoint/positive_part', 'profiles.dat' index 56 with lines lt 7 title 'slsqp/adjoint/positive_part', 'profiles.dat' index 57 with lines lt 8 title 'mma/adjoint/positive_part', 'profiles.dat' index 58 with lines lt 9 title 'ccsaq/adjoint/positive_part', 'profiles.dat' index 59 with lines lt 10 title 'ipopt/adjoint/positive_part'
unset multiplot
