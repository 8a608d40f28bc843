# How an ensemble's mean e departs from the deterministic surface as the spread of the ratios
# grows: scripts/ensemble_spread writes DIR/spread_S.csv for each spread S in SPREADS.
# Usage: gnuplot -e "dir='out/spread'; spreads='0 0.05 0.1'; png='a.png'" plot_spread.gp
set datafile separator ','
set datafile columnheaders   # columns by the names of the header row
set terminal pngcairo size 1200,520 noenhanced
set output png
set logscale x
set format x '%.0e'
set autoscale xfix
set grid
set multiplot layout 1,2
set xlabel 'V*'
set ylabel 'mean e over the realisations'
set yrange [0:1.05]
set key bottom left
plot for [s in spreads] sprintf('%s/spread_%s.csv', dir, s) using 'V_star':'e_mean' with lines lw 2 title sprintf('spread %s', s), \
     sprintf('%s/spread_0.csv', dir) using 'V_star':'e_deterministic' with points pt 6 ps 0.8 lc rgb 'black' title 'deterministic'
set ylabel 'mean e - e(deterministic)   (bars: 2 standard errors)'
set autoscale y
set key top left
plot for [s in spreads] sprintf('%s/spread_%s.csv', dir, s) using 'V_star':(column('e_mean') - column('e_deterministic')):(2 * column('e_sem')) with yerrorlines pt 7 ps 0.4 title sprintf('spread %s', s)
unset multiplot
