set terminal pngcairo noenhanced size 1000,380 font ',10'
set output 'work_precision.png'
set multiplot layout 1,1 rowsfirst title 'work-precision of the design gradients, problems/scenes/tramway.yaml'
set key outside right
set grid
set title ''
set xlabel 'wall time [s]'
set ylabel 'largest relative error of the gradients'
set logscale y
set format y "%.0e"
set logscale x
set format x "%.0e"
set yrange [*:*]
plot 'work_precision.dat' index 0 with linespoints title 'adjoint', 'work_precision.dat' index 1 with linespoints title 'continuous-adjoint', 'work_precision.dat' index 2 with linespoints title 'direct', 'work_precision.dat' index 3 with linespoints title 'fd_forward', 'work_precision.dat' index 4 with linespoints title 'fd_central'
unset multiplot
