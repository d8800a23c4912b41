#?RADIANCE
SOFTWARE= x
rsplit -ih -iH "-t " -oh -oH a -oa2 b
NCOMP=2
FORMAT=ascii

-Y        1 +X        3
2 3 
5 6 
8 9 
