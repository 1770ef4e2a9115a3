set terminal pngcairo noenhanced size 1000,760 font ',10'
set output 'convergence.png'
set multiplot layout 2,1 title 'convergence on problems/scenes/tramway.yaml'
set key outside right
set grid
set xlabel 'simulations'
set ylabel 'cost'
unset logscale y
plot 'convergence.dat' index 0 with linespoints title 'sdcc/adjoint/positive_part ε=1e-06', 'convergence.dat' index 1 with linespoints title 'slsqp/adjoint/positive_part ε=1e-06', 'convergence.dat' index 2 with linespoints title 'mma/adjoint/positive_part ε=1e-06', 'convergence.dat' index 3 with linespoints title 'ccsaq/adjoint/positive_part ε=1e-06', 'convergence.dat' index 4 with linespoints title 'ipopt/adjoint/positive_part ε=1e-06'
set xlabel 'simulations'
set ylabel 'max violation (0 drawn at 1e-12)'
set logscale y
plot 'convergence.dat' index 5 with linespoints title 'sdcc/adjoint/positive_part ε=1e-06', 'convergence.dat' index 6 with linespoints title 'slsqp/adjoint/positive_part ε=1e-06', 'convergence.dat' index 7 with linespoints title 'mma/adjoint/positive_part ε=1e-06', 'convergence.dat' index 8 with linespoints title 'ccsaq/adjoint/positive_part ε=1e-06', 'convergence.dat' index 9 with linespoints title 'ipopt/adjoint/positive_part ε=1e-06'
unset multiplot
