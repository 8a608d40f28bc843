# One metric of validate.csv as 3x3 maps (rows E/sigma_y, columns H*/h0), fx against fz.
# Usage: gnuplot -e "csv='v.csv'; col=7; name='dP_asym_exact_004'; png='m.png'" validate_map.gp
set datafile separator ','
set terminal pngcairo size 1500,1200 noenhanced font ',10'
set output png
set palette defined (0 '#ffffff', 0.05 '#fde0a0', 0.10 '#f08030', 0.3 '#a01010')
set cbrange [0:0.3]
set xrange [1.0:2.0]
set yrange [1.05:1.95]
set xlabel 'fz'
set ylabel 'fx'
unset key
set multiplot layout 3,3 title sprintf('%s (column %d of %s); orange and darker: >= 10%%', name, col, csv)
do for [E in "100 300 1000"] {
    do for [H in "3 10 100"] {
        set title sprintf('E/sigma_y = %s, H*/h0 = %s', E, H)
        plot csv skip 1 using (($3 == E+0 && $4 == H+0) ? $2 : 1/0):1:(column(col)) with points pt 5 ps 7 lc palette, \
             '' skip 1 using (($3 == E+0 && $4 == H+0) ? $2 : 1/0):1:(column(col) == column(col) ? sprintf('%.3f', column(col)) : 'n/a') with labels font ',9'
    }
}
unset multiplot
