#!/usr/bin/env bash
# nasty_inputs_gen.sh DIR: writes the nasty inputs of check_nasty_inputs.sh into DIR
set -euo pipefail
d="$1"; mkdir -p "$d"; cd "$d"
cube_v='v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n'
cube_l='l 1 2\nl 2 3\nl 3 4\nl 4 1\nl 5 6\nl 6 7\nl 7 8\nl 8 5\nl 1 5\nl 2 6\nl 3 7\nl 4 8\n'
cube_f='f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n'
printf '' > empty.obj
printf '' > empty.off
printf '# only a comment\n' > comment_only.obj
printf "$cube_v" > points_only.obj
printf "$cube_v$cube_l" > cube_wire.obj
printf "$cube_v$cube_f" > cube_mesh.obj
printf "$cube_v$cube_f" > CUBE_UPPER.OBJ
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2 3 4 1\n' > lone_square.obj
printf "${cube_v}l 1 2\nl 2 3\nl 3 4\nl 4 1\nl 5 6\nl 6 7\nl 7 8\nl 8 5\nl 1 5\nl 2 6\nl 3 7\n" > cube_missing_edge.obj
printf "$cube_v${cube_l}l 1 3\nl 2 4\n" > cube_crossing_diagonals.obj
printf "$cube_v${cube_l}l 1 99\n" > line_index_out_of_range.obj
printf "$cube_v${cube_f}f 1 2 99\n" > face_index_out_of_range.obj
printf 'v 0 0 nan\nv 1 0 0\nv 0 1 0\nl 1 2 3 1\n' > nan.obj
printf 'v 0 0 1e400\nv 1 0 0\nv 0 1 0\nl 1 2 3 1\n' > overflow_coordinate.obj
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 1\n' > self_loop.obj
printf 'v 0 0\n' > short_vertex.obj
printf 'vertices 3\n0 0 0\n1 0 0\n' > truncated.edges
printf 'vertices -1\n' > negative_count.edges
printf 'vertices 99999999999\n' > huge_count.edges
printf '\xff\xfe\x00\x01garbage\x00\x00' > binary_garbage.obj
# scales and far away (corners in the order of cube_v)
corners="0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1"
for s in 1e-300 1e-12 1e12 1e300; do
  awk -v s="$s" -v c="$corners" 'BEGIN{split(c,C," ");for(k=1;k<=24;k+=3)printf "v %.17g %.17g %.17g\n",C[k]*s,C[k+1]*s,C[k+2]*s}' > "cube_$s.obj"
  printf "$cube_l" >> "cube_$s.obj"
done
awk -v c="$corners" 'BEGIN{split(c,C," ");for(k=1;k<=24;k+=3)printf "v %.17g %.17g %.17g\n",C[k]+1e12,C[k+1]-1e12,C[k+2]+1e12}' > cube_far.obj
printf "$cube_l" >> cube_far.obj
# K_n on the moment curve
for n in 7 12; do
  awk -v n="$n" 'BEGIN{for(i=1;i<=n;i++)printf "v %d %d %d\n",i,i*i,i*i*i; for(a=1;a<=n;a++)for(b=a+1;b<=n;b++)printf "l %d %d\n",a,b}' > "k$n.obj"
done
# 10^5 duplicate edges
{ printf "$cube_v$cube_l"; awk 'BEGIN{for(i=0;i<100000;i++)print "l 1 2"}'; } > dup_1e5.obj
# a 1,000-gon prism, as a mesh (OFF) and as a wireframe (OBJ)
awk 'BEGIN{n=1000;pi=atan2(0,-1);print "OFF";print 2*n, n+2, 0;
  for(k=0;k<2;k++)for(i=0;i<n;i++)printf "%.17g %.17g %d\n",cos(2*pi*i/n),sin(2*pi*i/n),k;
  printf "%d",n;for(i=n-1;i>=0;i--)printf " %d",i;print "";
  printf "%d",n;for(i=0;i<n;i++)printf " %d",n+i;print "";
  for(i=0;i<n;i++){j=(i+1)%n;printf "4 %d %d %d %d\n",i,j,n+j,n+i}}' > prism_1000.off
awk 'BEGIN{n=1000;pi=atan2(0,-1);
  for(k=0;k<2;k++)for(i=0;i<n;i++)printf "v %.17g %.17g %d\n",cos(2*pi*i/n),sin(2*pi*i/n),k;
  for(k=0;k<2;k++)for(i=0;i<n;i++)printf "l %d %d\n",k*n+i+1,k*n+(i+1)%n+1;
  for(i=0;i<n;i++)printf "l %d %d\n",i+1,n+i+1}' > prism_1000.obj
# 4,096 separate cubes
awk 'BEGIN{e="1 2 2 4 4 3 3 1 5 6 6 8 8 7 7 5 1 5 2 6 3 7 4 8";split(e,E," ");nv=0;
  for(i=0;i<16;i++)for(j=0;j<16;j++)for(k=0;k<16;k++){for(c=0;c<8;c++)printf "v %d %d %d\n",2*i+c%2,2*j+int(c/2)%2,2*k+int(c/4);
  for(q=1;q<=24;q+=2)printf "l %d %d\n",nv+E[q],nv+E[q+1];nv+=8}}' > cubes_4096.obj
# 20,000 coplanar points
awk 'BEGIN{srand(7);print "OFF";print 20000,0,0;for(i=0;i<20000;i++)printf "%.17g %.17g 0\n",rand(),rand()}' > coplanar_20000.off
# 20,000 points on a circle (every point a hull vertex: the hull is a 20,000-gon, two faces back
# to back, 39,996 triangles), and that 20,000-gon as two polygon faces
awk 'BEGIN{n=20000;pi=atan2(0,-1);print "OFF";print n,0,0;for(i=0;i<n;i++)printf "%.17g %.17g 0\n",cos(2*pi*i/n),sin(2*pi*i/n)}' > circle_20000.off
awk 'BEGIN{n=20000;pi=atan2(0,-1);print "OFF";print n,2,0;for(i=0;i<n;i++)printf "%.17g %.17g 0\n",cos(2*pi*i/n),sin(2*pi*i/n);
  printf "%d",n;for(i=0;i<n;i++)printf " %d",i;print "";printf "%d",n;for(i=n-1;i>=0;i--)printf " %d",i;print ""}' > twogons_20000.off
# flat sheet (closed, zero volume) and an open surface
printf 'OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n4 3 2 1 0\n' > folded_sheet.off
printf 'OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n' > open_square.off
printf 'OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n' > tetra.off
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n' > degenerate_triangle.off
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n' > bad_header.ply
printf 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n' > truncated.stl
printf '3dcl 1\nvertices 1\nv 0 0 0 0 edges\n' > truncated.3dcl
# Edge 0 a loop (issue 35: clang's UBSan saw a null pointer stepped past).
printf '3dcl 1\nvertices 2\nv 0 0 0 0 edges +0 -0\nv 1 1 0 0 edges\nedges 1\ne 0 0 0 faces volumes\nfaces 0\nvolumes 0\nend\n' > loop_edge.3dcl
printf 'solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid x\n' > all_degenerate.stl
# SWC
printf '1 1 0 0 0 1 -1\n2 3 10 0 0 1 1\n3 3 20 0 0 0 2\n' > zero_radius.swc
printf '1 1 0 0 0 1 -1\n2 3 10 0 0 1 5\n' > missing_parent.swc
printf '1 1 0 0 0 1 -1\n2 3 0 0 0 1 1\n' > coincident_nodes.swc
printf '1 1 0 0 0 1 2\n2 3 10 0 0 1 1\n' > parent_cycle.swc
printf '' > empty.swc
# An edge of 0.01 r before a 20-degree turn (issue 35): merged, not folded.
printf '1 1 0 0 0 1 -1\n2 3 5 0 0 1 1\n3 3 5.01 0 0 1 2\n4 3 9.7085 1.7101 0 1 3\n' > short_edge_turn.swc
# drawings
printf '<svg xmlns="http://www.w3.org/2000/svg"></svg>\n' > empty.svg
printf '<svg xmlns="http://www.w3.org/2000/svg"><line x1="0" y1="0" x2="1" y2="1"/>\n' > unclosed.svg
printf 'not xml at all\n' > not_xml.svg
# drawings with arcs
printf 'j 0 0\nj 1 0\na 0 1 0 1 0 0 1\n' > zero_radius_arc.txt
printf 'j 0 0\nj 1 0\na 0 0 1 1 0 0 1\n' > closed_arc.txt
printf 'j 0 0\nj 2 0\nj 2 2\ne 0 1\ne 1 2\na 2 0 2 2 0 0 1\n' > lone_arc.txt
printf '<svg xmlns="http://www.w3.org/2000/svg"><circle cx="5" cy="5" r="2"/></svg>\n' > circle.svg
