set terminal pngcairo noenhanced size 1300,380 font ',10'
set output 'convergence.png'
set multiplot layout 1,2 rowsfirst title 'convergence on problems/suite/clothoid_transition.yaml'
set key top right font ',8'
set grid
set title 'grid_max, adjoint'
set xlabel 'simulations'
set ylabel 'cost'
unset logscale y
set format y
unset logscale x
set format x
set yrange [*:1]
plot 'convergence.dat' index 0 with linespoints title 'sdcc', 'convergence.dat' index 1 with linespoints title 'slsqp', 'convergence.dat' index 2 with linespoints title 'mma', 'convergence.dat' index 3 with linespoints title 'ccsaq', 'convergence.dat' index 4 with linespoints title 'ipopt'
set title 'grid_max, adjoint'
set xlabel 'simulations'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
set format y "%.0e"
unset logscale x
set format x
set yrange [*:*]
plot 'convergence.dat' index 5 with linespoints title 'sdcc', 'convergence.dat' index 6 with linespoints title 'slsqp', 'convergence.dat' index 7 with linespoints title 'mma', 'convergence.dat' index 8 with linespoints title 'ccsaq', 'convergence.dat' index 9 with linespoints title 'ipopt'
unset multiplot
