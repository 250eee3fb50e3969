set terminal pngcairo size 900,600
set output 'docs/work-precision/work_precision.png'
set logscale xy
set format x '1e%L'
set format y '1e%L'
set xlabel 'error (relative to channel amplitude)'
set ylabel 'wall time [s]'
set key outside right
set grid
set title 'work-precision: scenes/demo.yaml'
plot 'docs/work-precision/work_precision.dat' index 0 using 1:2 with linespoints title 'ida', 'docs/work-precision/work_precision.dat' index 1 using 1:2 with linespoints title 'cvode-bdf', 'docs/work-precision/work_precision.dat' index 2 using 1:2 with linespoints title 'cvode-adams', 'docs/work-precision/work_precision.dat' index 3 using 1:2 with linespoints title 'generalized-alpha', 'docs/work-precision/work_precision.dat' index 4 using 1:2 with linespoints title 'linear-acceleration'
