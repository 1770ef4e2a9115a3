set terminal pngcairo noenhanced size 900,600
set output 'work_precision_chain8.png'
set title "chain8: work-precision, Simbody 3.7 and MuJoCo 2.2.2 vs mbsopt\nSimbody: Release build of Debian's source package (-O2 -DNDEBUG)"
set logscale xy
set format x '1e%T'
set format y '1e%T'
set xlabel 'max abs joint-angle error at the output times [rad]'
set ylabel 'wall time of the integration [s] (median)'
set grid
set key top right
set xrange [*:*] reverse
plot 'work_precision_chain8.dat' index 0 using 1:2 with linespoints lw 3 pt 7 lc rgb '#d62728' title 'mbsopt Newmark', \
     'work_precision_chain8.dat' index 1 using 1:2 with linespoints lw 3 pt 11 lc rgb '#e377c2' title 'mbsopt Newmark, fast steps', \
     'work_precision_chain8.dat' index 2 using 1:2 with linespoints lw 3 pt 5 lc rgb '#ff9896' title 'mbsopt adaptive', \
     'work_precision_chain8.dat' index 3 using 1:2 with linespoints lw 3 pt 9 lc rgb '#8c1a1a' title 'mbsopt extrapolation', \
     'work_precision_chain8.dat' index 4 using 1:2 with linespoints lw 1.5 pt 10 lc rgb '#aec7e8' title 'mujoco Euler', \
     'work_precision_chain8.dat' index 5 using 1:2 with linespoints lw 1.5 pt 14 lc rgb '#1f3f9f' title 'mujoco RK4', \
     'work_precision_chain8.dat' index 6 using 1:2 with linespoints lw 1.5 pt 12 lc rgb '#6baed6' title 'mujoco implicit', \
     'work_precision_chain8.dat' index 7 using 1:2 with linespoints lw 1.5 pt 8 lc rgb '#17becf' title 'simbody CPodes', \
     'work_precision_chain8.dat' index 8 using 1:2 with linespoints lw 1.5 pt 4 lc rgb '#2ca02c' title 'simbody RungeKuttaFeldberg', \
     'work_precision_chain8.dat' index 9 using 1:2 with linespoints lw 1.5 pt 6 lc rgb '#98df8a' title 'simbody RungeKuttaMerson'
