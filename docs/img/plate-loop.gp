# The plate loop figure (docs/validation.md, "The plate loop"): gnuplot docs/img/plate-loop.gp
# from the repository root. Inputs: docs/data/plate-loop-mu0.3.csv (the long validation's
# samples at mu = 0.3, written with SNAPJUMP_PLATE_LOOP_CSV=docs/data/plate-loop) and
# docs/data/contact-branches-nu0.45.csv (`build/snapjump contact --nu 0.45 --curves ...`).
E = 1.2e6; h = 2e-3; R = 30e-3; nu = 0.45
kappa = 12 * (1 - nu**2)
Fc = E * h**3 / R
FN(N) = N * Fc / kappa              # contact solver's force in newtons
emm(eh) = 1e3 * eh * h / sqrt(kappa) # and its plane displacement in millimetres
aFlo = 5.0612; aFhi = 8.0401         # alpha_F bounds at nu = 0.45 (snapjump contact --nu 0.45)
set terminal pngcairo size 900,900 enhanced font 'DejaVu Sans,12' linewidth 1.5
set output 'docs/img/plate-loop.png'
set datafile separator ','
set multiplot layout 2,1 title "(30, 2.0) mm shell pressed by the plate at 0.05 m/s and withdrawn (no gas, {/Symbol m} = 0.3)"
set xrange [0:9.5]
set ylabel 'plate force F (N)'
set key top left
set grid
set object 1 rect from graph 0, first aFlo*Fc to graph 1, first aFhi*Fc fc rgb '#8c8c8c' fs transparent solid 0.3 noborder
plot 'docs/data/plate-loop-mu0.3.csv' every ::2 using ($4 == 0 ? 1e3*$1 : 1/0):2 with lines lc rgb '#1f77b4' title 'MPM, pressing', \
     '' every ::2 using ($4 == 1 ? 1e3*$1 : 1/0):2 with lines lc rgb '#ff7f0e' title 'MPM, withdrawing', \
     'docs/data/contact-branches-nu0.45.csv' every ::1 using (strcol(1) eq 'disk' ? emm($4) : 1/0):(FN($3)) with lines lc rgb 'black' title 'contact solver: disk branch', \
     '' every ::1 using (strcol(1) eq 'ring' ? emm($4) : 1/0):(FN($3)) with lines dt 2 lc rgb 'black' title 'ring branch (axisymmetric)', \
     1/0 with boxes fc rgb '#8c8c8c' fs transparent solid 0.3 noborder title '{/Symbol a}_F bounds (N_- to N_+)'
unset object 1
set xlabel 'rim travel e past first touch (mm)'
set ylabel 'apex height above the plate w (mm)'
set arrow 1 from graph 0, first 0.9 to graph 1, first 0.9 nohead dt 3 lc rgb '#7f7f7f'
set label 1 'w = 0.03 R (onset criterion)' at graph 0.02, first 1.4 tc rgb '#7f7f7f'
plot 'docs/data/plate-loop-mu0.3.csv' every ::2 using ($4 == 0 ? 1e3*$1 : 1/0):(1e3*$3) with lines lc rgb '#1f77b4' title 'pressing', \
     '' every ::2 using ($4 == 1 ? 1e3*$1 : 1/0):(1e3*$3) with lines lc rgb '#ff7f0e' title 'withdrawing'
unset multiplot
