# An ensemble's e against V* from a `cantact run` ensemble CSV: the mean with the 5-95 % band
# of the realisations, the median, and e of the deterministic surface (spread 0); or, with
# landings = 1, the same over a body's landings with e at body.position beside them.
# Usage: gnuplot -e "csv='a.csv'; png='a.png'[; landings=1]" plot_ensemble.gp
set datafile separator ','
set datafile columnheaders   # columns by the names of the header row
set terminal pngcairo size 900,600 noenhanced
set output png
set logscale x
set format x '%.0e'
set autoscale xfix
# with a mass the statistics end with the impact speed: plotted against it
speeds = 0
if (system(sprintf("head -1 '%s' | grep -c ',v_impact_m_per_s'", csv)) + 0 > 0) speeds = 1
x = speeds ? 'v_impact_m_per_s' : 'V_star'
set xlabel speeds ? 'impact speed v1 [m/s]' : 'V* = sqrt(m v1^2 / (2 l0 E h0))'
set ylabel 'coefficient of restitution e'
if (!exists("landings")) landings = 0
samples = landings ? 'landings' : 'realisations'
reference = landings ? 'e_at_position' : 'e_deterministic'
stats csv using samples every ::0::0 nooutput
R = STATS_max
set yrange [0:1.05]
set grid
set key bottom left
name = system(sprintf("basename '%s' .csv", csv))
set title landings ? sprintf('cantact: %s, %d landings of the body per speed', name, R) : \
    sprintf('cantact: %s, random Cantor surface, %d realisations per V*', name, R)
plot csv using x:'e_q05':'e_q95' with filledcurves fc rgb '#9ecae1' fs transparent solid 0.6 title '5-95 % of the '.samples, \
     '' using x:'e_q50' with lines dashtype 3 lw 1.5 lc rgb '#08519c' title 'median', \
     '' using x:'e_mean':'e_sem' with yerrorlines pt 7 ps 0.5 lw 1.5 lc rgb '#08519c' title 'mean +- standard error', \
     '' using x:reference with lines lw 2 dashtype 2 lc rgb '#d62728' title (landings ? 'apex at body.position' : 'deterministic surface (spread 0)')
