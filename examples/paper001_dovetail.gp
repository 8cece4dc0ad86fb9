# Paper 001, figures 16 and 17 (the dovetail joint), as far as a half-plane model goes: the flank approximated as a
# rounded punch (flat half-length 0.166 mm, corner radius 19 mm, tilted 0.5 mrad), similar bodies E = 17 000 ksi,
# ν = 0.3, f = 0.5, at the four loads of their parametric study (65.625 to 262.5 lbf on 0.1 in: 656 to 2625 lbf/in),
# each with Q = 0.45 P. Run the four paper001_dovetail_*.json scenes, then, from the repository root:
#   gnuplot examples/paper001_dovetail.gp   (writes output/paper001_dovetail_tractions and _slip, .svg and .png)
set datafile separator ','
set grid
ksi = 6894757.293
um = 1e-6
mm = 1e-3
set xlabel 'x (mm)'
loads = '656 1313 1969 2625'
set terminal svg size 900,560 dynamic font 'sans,12'
set output 'output/paper001_dovetail_tractions.svg'
set ylabel 'traction (ksi)'
set yrange [0:120]
set key top right maxrows 4
plot for [k=1:4] sprintf('output/paper001_dovetail_%d/cycle.csv', k) skip 1 using ($1/mm):($2/ksi) \
       with lines lw 2 lc k title sprintf('p, %s lbf/in', word(loads, k)), \
     for [k=1:4] sprintf('output/paper001_dovetail_%d/cycle.csv', k) skip 1 using ($1/mm):($3/ksi) \
       with lines lw 2 dt 2 lc k title sprintf('q at the top, %s lbf/in', word(loads, k))
set terminal pngcairo size 900,560 font 'sans,11'
set output 'output/paper001_dovetail_tractions.png'
replot
set terminal svg size 900,560 dynamic font 'sans,12'
set output 'output/paper001_dovetail_slip.svg'
set ylabel 'slip range over a steady cycle (µm)'
set yrange [0:*]
set key top center
plot for [k=1:4] sprintf('output/paper001_dovetail_%d/cycle.csv', k) skip 1 using ($1/mm):($7/um) \
       with lines lw 2 lc k title sprintf('%s lbf/in', word(loads, k))
set terminal pngcairo size 900,560 font 'sans,11'
set output 'output/paper001_dovetail_slip.png'
replot
