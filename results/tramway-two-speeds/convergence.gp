set terminal pngcairo noenhanced size 1300,380 font ',10'
set output 'convergence.png'
set multiplot layout 1,2 rowsfirst title 'convergence on results/tramway-two-speeds/tramway_two_speeds.yaml'
set key top right font ',8'
set grid
set title 'positive_part, adjoint'
set xlabel 'simulation-equivalents (simulations + gradients at their cost)'
set ylabel 'max_abs_a_lat'
unset logscale y
set format y
unset logscale x
set format x
set yrange [*:3.4851]
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
unset multiplot
