# gnuplot doc/raytraced-convergence.gp (from the source tree; Debian:
# gnuplot-nox) makes doc/raytraced-convergence.png from
# doc/raytraced-convergence.dat, which bench/raytraced writes: relative
# RMSE on room-floor against a 16384-ray render, by rays a pixel, pattern
# and sampler (solid: vndf, dashed: mis).
set terminal pngcairo size 720,480 font ",11"
set output "doc/raytraced-convergence.png"
set logscale xy
set xlabel "rays a pixel"
set ylabel "relative RMSE against 16384 rays (room-floor)"
set key top right
set grid
set xtics (4, 16, 64, 256, 1024)
plot "doc/raytraced-convergence.dat" using 1:2 with linespoints lc 1 pt 7 title "white", \
     "" using 1:3 with linespoints lc 2 pt 7 title "blue", \
     "" using 1:4 with linespoints lc 3 pt 7 title "deterministic", \
     "" using 1:5 with linespoints lc 1 pt 6 dashtype 2 title "white, mis", \
     "" using 1:6 with linespoints lc 2 pt 6 dashtype 2 title "blue, mis", \
     "" using 1:7 with linespoints lc 3 pt 6 dashtype 2 title "deterministic, mis", \
     "" using 1:(0.56624 * sqrt(4 / $1)) with lines lc 0 dashtype 3 title "K^-1/2"
