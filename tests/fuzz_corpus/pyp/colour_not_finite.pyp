*pattern
1 1 0.1 2
*Q
0 0 0 0
0.5 0 0 0
*E
0 1 0 0
1 0 1 0
*RGB
1 0 nan
0 0 1e400
