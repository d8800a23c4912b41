#?RADIANCE
rsplit "-t " -oh a -oa2 b
NCOMP=2
FORMAT=ascii

2 3 
5 6 
8 9 
