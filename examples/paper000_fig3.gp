# Paper 000, figure 3: b p / P against x / b for a/b = 0 (Hertz), 0.25, 0.5, 0.75 and 1 (sharp punch).
# Run the five paper000_fig3_ab_*.json scenes first, then, from the repository root:
#   gnuplot examples/paper000_fig3.gp      (writes output/paper000_fig3.svg and .png)
set datafile separator ','
set xlabel 'x / b'
set ylabel 'b p / P'
set grid
set key top right
set xrange [-1.05:1.05]
set yrange [0:2]
b = 0.5e-3
set terminal svg size 900,560 dynamic font 'sans,12'
set output 'output/paper000_fig3.svg'
plot 'output/paper000_fig3_ab_0/contact.csv' skip 1 using ($1/b):($3*b/2157687.26) with lines lw 2 title 'a/b = 0 (Hertz)', \
     'output/paper000_fig3_ab_025/contact.csv' skip 1 using ($1/b):($3*b/1478097.53) with lines lw 2 title 'a/b = 0.25', \
     'output/paper000_fig3_ab_05/contact.csv' skip 1 using ($1/b):($3*b/843660.71) with lines lw 2 title 'a/b = 0.5', \
     'output/paper000_fig3_ab_075/contact.csv' skip 1 using ($1/b):($3*b/311340.66) with lines lw 2 title 'a/b = 0.75', \
     'output/paper000_fig3_ab_1/contact.csv' skip 1 using ($1/b):($3*b/500000.0) with lines lw 2 title 'a/b = 1 (sharp)'
set terminal pngcairo size 900,560 font 'sans,11'
set output 'output/paper000_fig3.png'
replot
