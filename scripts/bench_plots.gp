# Plots of scripts/bench. Usage: gnuplot -e "dir='out/bench'" scripts/bench_plots.gp
set terminal pngcairo size 1000,680 font ",11"
set datafile separator ","
set datafile commentschars "#"
set key outside right top
set grid

# Error against run time, one point per method and rule; errors below 1e-17 drawn at 1e-17.
set output dir."/pareto.png"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "median run time per impact [s]"
set ylabel "|e - e_{ref}|"
machine = system("sed -n 's/^# machine: //p' ".dir."/methods.csv")
set title "Error against run time: fx = 1.5, fz = 1.3, H*/h0 = 10, E/sigma_y = 500, V* = 1e-3\n".machine noenhanced
err(c) = (column(11) > 1e-17 ? column(11) : 1e-17)
sel(m, r) = (strcol(1) eq m && strcol(4) eq r && strcol(8) ne "") ? column(8) : NaN
selm(m) = (strcol(1) eq m && strcol(8) ne "") ? column(8) : NaN
plot dir."/methods.csv" every ::1 using (selm("asymptotic")):(err(0)) with points pt 9 ps 2 title "asymptotic law", \
     "" every ::1 using (selm("series")):(err(0)) with points pt 11 ps 2 title "series", \
     "" every ::1 using (sel("stages-fractal", "breakpoints")):(err(0)) with points pt 7 ps 1.6 title "stage rods, fractal, breakpoints", \
     "" every ::1 using (sel("stages-fractal", "closed")):(err(0)) with points pt 6 ps 1.6 title "stage rods, fractal, closed forms", \
     "" every ::1 using (sel("stages-fractal", "curve")):(err(0)) with points pt 13 ps 1.8 title "stage rods, fractal, per speed on a built curve", \
     "" every ::1 using (sel("stages-fractal", "curve+check")):(err(0)) with points pt 12 ps 1.8 title "the same, with the closed-form check", \
     "" every ::1 using (sel("stages-auto", "breakpoints")):(err(0)) with points pt 5 ps 1.4 title "stage rods, auto, breakpoints", \
     "" every ::1 using (sel("stages-auto", "closed")):(err(0)) with points pt 4 ps 1.4 title "stage rods, auto, closed forms", \
     "" every ::1 using (sel("stages-auto", "trapezoid")):(err(0)) with points pt 1 title "stage rods, auto, trapezoid K", \
     "" every ::1 using (sel("stages-auto", "simpson")):(err(0)) with points pt 2 title "stage rods, auto, Simpson K", \
     "" every ::1 using (sel("stages-auto", "gauss")):(err(0)) with points pt 3 title "stage rods, auto, Gauss K", \
     "" every ::1 using (sel("segments", "breakpoints")):(err(0)) with linespoints pt 4 title "segment rods 8..26, breakpoints", \
     "" every ::1 using (sel("segments", "closed")):(err(0)) with points pt 12 title "segment rods, closed forms", \
     "" every ::1 using (sel("segments", "trapezoid")):(err(0)) with points pt 1 lc rgb "gray50" title "segment rods, trapezoid K", \
     "" every ::1 using (sel("segments", "simpson")):(err(0)) with points pt 2 lc rgb "gray50" title "segment rods, Simpson K", \
     "" every ::1 using (sel("segments", "gauss")):(err(0)) with points pt 3 lc rgb "gray50" title "segment rods, Gauss K", \
     dir."/pareto_front.csv" using 1:2 with steps lw 2 lc rgb "black" title "Pareto front" 

# Force assembly: bytes/s against bundle size, 1 and 2 threads, with the bandwidth lines.
set output dir."/assembly.png"
unset logscale y
set logscale x 2
set format x "2^{%L}"
set format y "%g"
set xlabel "rods"
set ylabel "GB/s (32 bytes per rod)"
set yrange [0:*]
set title "Force assembly against memory bandwidth\n".machine noenhanced
# rows alternate: 1 thread, then 2 threads, for each size
plot dir."/assembly.csv" every 2::1 using 1:($6 / 1e9) with linespoints pt 7 lc 1 title "assembly, 1 thread", \
     "" every 2::2 using 1:($6 / 1e9) with linespoints pt 5 lc 2 title "assembly, 2 threads", \
     "" every 2::1 using 1:($9 / 1e9) with lines dt 2 lc 1 title "read of 4 arrays, 1 thread", \
     "" every 2::2 using 1:($9 / 1e9) with lines dt 2 lc 2 title "read of 4 arrays, 2 threads", \
     "" every 2::2 using 1:($7 / 1e9) with lines dt 3 lc 3 title "triad, 2 threads"
