# e against the impact speed from a `cantact run` e CSV: in the scene's units (m/s) when the CSV
# carries v_impact_m_per_s (a scene given by mass and velocity), else against V*.
# Usage: gnuplot -e "csv='a.csv'; png='a.png'; name='a'; speeds=1; per=1.5" plot_e.gp
# (per: the scene's speed per unit V*, v_impact_m_per_s / V_star)
set datafile separator ','
set datafile columnheaders   # columns by the names of the header row
set terminal pngcairo size 900,600 noenhanced
set output png
set logscale x
set format x '%.0e'
set autoscale xfix
if (!exists("name")) name = 'cantact'
if (!exists("speeds")) speeds = 0
set ylabel 'coefficient of restitution e'
set yrange [0:1.1]
set grid
set key bottom left
stats csv using 'V_star_crit' every ::0::0 nooutput
vc = STATS_max
if (speeds) {
    # per: the speed per unit V* of this scene (v_impact / V*, from the caller)
    xc = vc * per
    set xlabel 'impact speed v1 [m/s]'
    set label sprintf(' first yield: v_c = %.3g m/s', xc) at xc, graph 0.3 left
    set title sprintf('e against the impact speed: %s', name)
} else {
    xc = vc
    set xlabel 'V* = sqrt(m v1^2 / (2 l0 E h0))'
    set label sprintf(' first yield: V*_c = %.3g', xc) at xc, graph 0.3 left
    set title sprintf('e against V*: %s', name)
}
set arrow from xc, graph 0 to xc, graph 1 nohead dashtype 2 lc rgb 'gray40'
if (speeds) {
    plot csv using 'v_impact_m_per_s':'e' with linespoints pt 7 ps 0.6 title 'e from the exact rods'
} else {
    plot csv using 'V_star':'e' with linespoints pt 7 ps 0.6 title 'e from the exact rods'
}
