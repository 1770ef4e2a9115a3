set terminal pngcairo noenhanced size 1300,380 font ',10'
set output 'convergence.png'
set multiplot layout 1,2 rowsfirst title 'convergence on problems/scenes/tramway.yaml'
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
set title 'positive_part ε=1e-07, adjoint: best 2.1893159 (the best reported; 0 drawn at 1e-10 of it)'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel '|max_abs_a_lat - best| [m/s²]'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:0.70743]
plot 'convergence.dat' index 0 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 1 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 2 with linespoints lt 3 title 'mma', 'convergence.dat' index 3 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 4 with linespoints lt 5 title 'ipopt', 'convergence.dat' index 5 with points pt 6 ps 2 lt 1 notitle, 'convergence.dat' index 6 with points pt 6 ps 2 lt 2 notitle, 'convergence.dat' index 7 with points pt 6 ps 2 lt 3 notitle, 'convergence.dat' index 8 with points pt 6 ps 2 lt 4 notitle, 'convergence.dat' index 9 with points pt 6 ps 2 lt 5 notitle
set title 'positive_part ε=1e-07, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:*]
plot 'convergence.dat' index 10 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 11 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 12 with linespoints lt 3 title 'mma', 'convergence.dat' index 13 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 14 with linespoints lt 5 title 'ipopt', 'convergence.dat' index 15 with points pt 6 ps 2 lt 1 notitle, 'convergence.dat' index 16 with points pt 6 ps 2 lt 2 notitle, 'convergence.dat' index 17 with points pt 6 ps 2 lt 3 notitle, 'convergence.dat' index 18 with points pt 6 ps 2 lt 4 notitle, 'convergence.dat' index 19 with points pt 6 ps 2 lt 5 notitle
unset multiplot
