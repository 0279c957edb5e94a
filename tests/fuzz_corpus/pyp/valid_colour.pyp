*pattern
1 1 0.1 2
*Q
0 0 0 0
0.5 0 0 0
*E
0 1 0 0
1 0 1 0
*RGB # linear yarn colour per vertex
1 0 0
0 0 1
