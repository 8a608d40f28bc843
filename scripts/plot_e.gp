# e against V* from a `cantact run` e CSV. Usage: gnuplot -e "csv='a.csv'; png='a.png'" plot_e.gp
set datafile separator ','
set datafile columnheaders   # columns by the names of the header row
set terminal pngcairo size 900,600 noenhanced
set output png
set logscale x
set format x '%.0e'
set autoscale xfix
set xlabel 'V* = sqrt(m v1^2 / (2 l0 E h0))'
set ylabel 'coefficient of restitution e'
set yrange [0:1.05]
set grid
set key bottom left
stats csv using 'V_star_crit' every ::0::0 nooutput
vc = STATS_max
set arrow from vc, graph 0 to vc, graph 1 nohead dashtype 2 lc rgb 'gray40'
set label sprintf('V*_c = %.3g', vc) at vc, graph 0.95 offset 1,0
set title sprintf('cantact: e(V*) from exact rods, %s', csv)
plot csv using 'V_star':'e' with linespoints pt 7 ps 0.6 title 'e (breakpoint quadrature)'
