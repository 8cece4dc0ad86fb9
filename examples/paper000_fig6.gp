# Paper 000, figure 6: K_I √b / P at the trailing edge against crack depth l / b for a/b = 0 (Hertz), 0.25, 0.5,
# 0.75 and 1 (sharp punch), at the top of the cycle: Q/fP = 0.4, f = 0.4, b σ_bulk / P = 0.1. The open-crack K_I, as
# the paper plots it (negative values mean the faces would close). The paper does not print its normalisation of K;
# this one makes the curves independent of the size of the contact.
# Run the five paper000_fig6_ab_*.json scenes first, then, from the repository root:
#   gnuplot examples/paper000_fig6.gp      (writes output/paper000_fig6.svg and .png)
set datafile separator ','
set xlabel 'crack depth l / b'
set ylabel 'K_I √b / P  (open crack, top of the cycle)'
set grid
set key top right
set xzeroaxis lt -1
b = 0.5e-3
K(P) = sqrt(b) / P
top(ph, v) = (strcol(2) eq 'top' && $1 == 0) ? v : NaN
set terminal svg size 900,560 dynamic font 'sans,12'
set output 'output/paper000_fig6.svg'
plot 'output/paper000_fig6_ab_0/sif.csv' skip 1 using ($3/b):(top(0, $5*K(2157687.26))) with linespoints lw 2 title 'a/b = 0 (Hertz)', \
     'output/paper000_fig6_ab_025/sif.csv' skip 1 using ($3/b):(top(0, $5*K(1478097.53))) with linespoints lw 2 title 'a/b = 0.25', \
     'output/paper000_fig6_ab_05/sif.csv' skip 1 using ($3/b):(top(0, $5*K(843660.71))) with linespoints lw 2 title 'a/b = 0.5', \
     'output/paper000_fig6_ab_075/sif.csv' skip 1 using ($3/b):(top(0, $5*K(311340.66))) with linespoints lw 2 title 'a/b = 0.75', \
     'output/paper000_fig6_ab_1/sif.csv' skip 1 using ($3/b):(top(0, $5*K(500000.0))) with linespoints lw 2 title 'a/b = 1 (sharp)'
set terminal pngcairo size 900,560 font 'sans,11'
set output 'output/paper000_fig6.png'
replot
