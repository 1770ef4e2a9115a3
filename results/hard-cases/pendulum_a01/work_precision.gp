set terminal pngcairo noenhanced size 1000,380 font ',10'
set output 'work_precision.png'
set multiplot layout 1,1 rowsfirst title 'work-precision of the integrator, problems/scenes/hard/pendulum_a01.yaml'
set key outside right
set grid
set title ''
set xlabel 'wall time [s]'
set ylabel 'largest absolute error [SI]'
set logscale y
set format y "%.0e"
set logscale x
set format x "%.0e"
set yrange [*:*]
plot 'work_precision.dat' index 0 with linespoints title 'newmark', 'work_precision.dat' index 1 with linespoints title 'fast-newton'
unset multiplot
