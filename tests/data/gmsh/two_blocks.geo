// Two unit cubes side by side, each its own physical volume, with named faces and a
// named corner: test data of the gmsh reader (tests/io/mesh/test_gmsh_io.cpp).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {2, 0, 0, 1, 1, 1};
Physical Volume("left") = {1};
Physical Volume("right") = {2};
Physical Surface("left_bottom") = {5};
Physical Surface("right_top") = {12};
Physical Point("left_top_corner") = {1};
// Made with gmsh 4.8.4 (Debian), element size 0.5:
//   gmsh -3 two_blocks.geo -clmin 0.5 -clmax 0.5 -order 2 -format msh41 [-bin] -o two_blocks_{ascii,bin}41.msh
//   gmsh -3 two_blocks.geo -clmin 0.5 -clmax 0.5 -order 2 -format msh22 [-bin] -o two_blocks_{ascii,bin}22.msh
//   gmsh -3 two_blocks.geo -clmin 0.5 -clmax 0.5 -order 1 -format msh41 -bin -o two_blocks_tet4_bin41.msh
//   gmsh -3 two_blocks.geo -clmin 0.5 -clmax 0.5 -order 1 -format msh22 -bin -o two_blocks_tet4_bin22.msh
