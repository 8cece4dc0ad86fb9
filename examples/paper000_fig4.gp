# Paper 000, figure 4: the peak pressure p_max b / P of the rounded punch against a/b. The curve is the sweep of
# examples/paper000_fig4.json over the flat half-length a at fixed P and R (a/b follows from the contact each run
# finds); the points are PHYSICS.md's closed-form values, and a/b → 0 is Hertz, 2/π. From the repository root:
#   fretwear sweep examples/paper000_fig4.json \
#     --vary profile.a=0.01e-3,0.05e-3,0.1e-3,0.15e-3,0.2e-3,0.25e-3,0.3e-3,0.4e-3,0.5e-3,0.6e-3,0.8e-3,1e-3,1.5e-3,2e-3,3e-3
#   gnuplot examples/paper000_fig4.gp      (writes output/paper000_fig4.svg and .png)
# sweep.csv quotes contact.extent as "[left,right]"; gnuplot reads column 5 up to the comma: "[left". The contact
# is symmetric, so b = −left.
set datafile separator ','
P = 843660.71
b(s) = -real(s[strstrt(s, '[') + 1:strlen(s)])
set xlabel 'a / b'
set ylabel 'p_{max} b / P'
set grid
set key top left
set xrange [0:1]
set yrange [0:2]
$closed << EOD
0,0.636620
0.25,0.610540
0.5,0.670453
0.75,0.870333
0.9,1.316371
EOD
set terminal svg size 900,560 dynamic font 'sans,12'
set output 'output/paper000_fig4.svg'
plot 'output/paper000_fig4/sweep/sweep.csv' skip 1 using ($1 / b(strcol(5))):($4 * b(strcol(5)) / P) with linespoints lw 2 \
       title 'fretwear (2048 cells)', \
     $closed using 1:2 with points pt 7 ps 1.5 title 'closed form (PHYSICS.md; a/b = 0: Hertz, 2/π)'
set terminal pngcairo size 900,560 font 'sans,11'
set output 'output/paper000_fig4.png'
replot
