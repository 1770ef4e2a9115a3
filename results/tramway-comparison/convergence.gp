set terminal pngcairo noenhanced size 1300,1520 font ',10'
set output 'convergence.png'
set multiplot layout 4,2 rowsfirst title 'convergence on problems/scenes/tramway.yaml'
set key top right font ',8'
set grid
set title 'positive_part, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max_abs_a_lat'
unset logscale y
set format y
unset logscale x
set format x
set yrange [*:2.54303]
plot 'convergence.dat' index 0 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 1 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 2 with linespoints lt 3 title 'mma', 'convergence.dat' index 3 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 4 with linespoints lt 5 title 'ipopt'
set title 'positive_part, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:*]
plot 'convergence.dat' index 5 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 6 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 7 with linespoints lt 3 title 'mma', 'convergence.dat' index 8 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 9 with linespoints lt 5 title 'ipopt'
set title 'squared_positive_part, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max_abs_a_lat'
unset logscale y
set format y
unset logscale x
set format x
set yrange [*:2.54303]
plot 'convergence.dat' index 10 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 11 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 12 with linespoints lt 3 title 'mma', 'convergence.dat' index 13 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 14 with linespoints lt 5 title 'ipopt'
set title 'squared_positive_part, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:*]
plot 'convergence.dat' index 15 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 16 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 17 with linespoints lt 3 title 'mma', 'convergence.dat' index 18 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 19 with linespoints lt 5 title 'ipopt'
set title 'grid_max, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max_abs_a_lat'
unset logscale y
set format y
unset logscale x
set format x
set yrange [*:2.54303]
plot 'convergence.dat' index 20 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 21 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 22 with linespoints lt 3 title 'mma', 'convergence.dat' index 23 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 24 with linespoints lt 5 title 'ipopt'
set title 'grid_max, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:*]
plot 'convergence.dat' index 25 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 26 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 27 with linespoints lt 3 title 'mma', 'convergence.dat' index 28 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 29 with linespoints lt 5 title 'ipopt'
set title 'ks, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max_abs_a_lat'
unset logscale y
set format y
unset logscale x
set format x
set yrange [*:2.54303]
plot 'convergence.dat' index 30 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 31 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 32 with linespoints lt 3 title 'mma', 'convergence.dat' index 33 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 34 with linespoints lt 5 title 'ipopt'
set title 'ks, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:*]
plot 'convergence.dat' index 35 with linespoints lt 1 title 'sdcc', 'convergence.dat' index 36 with linespoints lt 2 title 'slsqp', 'convergence.dat' index 37 with linespoints lt 3 title 'mma', 'convergence.dat' index 38 with linespoints lt 4 title 'ccsaq', 'convergence.dat' index 39 with linespoints lt 5 title 'ipopt'
unset multiplot
