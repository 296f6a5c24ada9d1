# Fig. 3(a) of the paper: the lift H_l against delta_p_j / p_c, from the sweep table runs/sweep-lift-axi/sweep.csv.
# Written by `snapjump plot sweep`; edit and redraw with `gnuplot lift-axi.gp` in this folder.
# The band is the theory's H_l = R (1 - cos phi) - alpha_e h (fully inverted limit) of
# each run, sorted by delta_p_j / p_c and carried flat to the edges.
set terminal pngcairo size 1000,750 enhanced font 'DejaVu Sans,15' linewidth 1.5 background rgb 'white'
set encoding utf8
set output 'lift-axi.png'
$sim << EOD
# delta_p_j/p_c  H_l [mm]
0.1 0
0.15 0
0.2 9.518168408
0.25 16.29887251
0.3 17.5749129
0.4 18.13308658
0.5 18.43865496
0.6 18.7030218
0.8 18.97386064
1 19.13600861
EOD
$band << EOD
# delta_p_j/p_c  H_l_lo [mm]  H_l_hi [mm]
0.028 16.07270092 21.33600345
0.1 16.07270092 21.33600345
0.15 16.07270092 21.33600345
0.2 16.07270092 21.33600345
0.25 16.07270092 21.33600345
0.3 16.07270092 21.33600345
0.4 16.07270092 21.33600345
0.5 16.07270092 21.33600345
0.6 16.07270092 21.33600345
0.8 16.07270092 21.33600345
1 16.07270092 21.33600345
1.072 16.07270092 21.33600345
EOD
set xrange [0.028:1.072]
set offsets 0, 0, graph 0.08, graph 0.08
set xlabel 'pressure difference at release δp_j / p_c [-]'
set ylabel 'lift H_l [mm]'
set title 'lift of the container up to the contact transition'
set key top left Left reverse opaque box lc rgb '#c0c0c0'
set grid lc rgb '#e0e0e0'
plot $band using 1:2:3 with filledcurves fc rgb '#8c8c8c' fs transparent solid 0.3 noborder title 'theory bounds (contact solver)', $sim using 1:2 with points pt 6 ps 1.6 lw 1.5 lc rgb '#1f77b4' title 'simulation'
