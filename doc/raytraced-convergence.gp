# gnuplot doc/raytraced-convergence.gp (from the source tree; Debian:
# gnuplot-nox) makes
# doc/raytraced-convergence.png from doc/raytraced-convergence.dat, which
# bench/raytraced writes: relative RMSE on room-floor against a
# 16384-ray render, by rays a pixel and pattern.
set terminal pngcairo size 720,480 font ",11"
set output "doc/raytraced-convergence.png"
set logscale xy
set xlabel "rays a pixel"
set ylabel "relative RMSE against 16384 rays (room-floor)"
set key top right
set grid
set xtics (4, 16, 64, 256, 1024)
plot "doc/raytraced-convergence.dat" using 1:2 with linespoints title "white", \
     "" using 1:3 with linespoints title "blue", \
     "" using 1:4 with linespoints title "deterministic", \
     "" using 1:(0.56624 * sqrt(4 / $1)) with lines dashtype 2 title "K^-1/2"
