# gnuplot doc/fidelity.gp (from the source tree; Debian: gnuplot-nox)
# makes doc/fidelity.png from doc/fidelity.dat, which bench/fidelity
# writes: each mode's mean relative RMSE against the truth over the
# scenes, by its cost in nanoseconds a pixel.
set terminal pngcairo size 720,480 font ",11"
set output "doc/fidelity.png"
set logscale x
set xlabel "nanoseconds a pixel (reflect-shade, 2 threads)"
set ylabel "mean relative RMSE against the truth"
set grid
set key off
set offsets graph 0.05, graph 0.25, graph 0.1, graph 0.05
plot "doc/fidelity.dat" using 2:3 with points pt 7 ps 1.5 lc 1, \
     "" using 2:3:1 with labels offset 0,1
