// Checks that a set of lattice tetrahedra is a conforming mesh of the root cube, two ways:
// an exact face-matching check of our own, and TetGen's reconstruction of the mesh.
// Tests only.
#ifndef atpConformityCheck_h
#define atpConformityCheck_h

#include "atpTetra.h"

#include <string>
#include <vector>

namespace atp
{
namespace testing
{

/// Empty when conforming, otherwise what is wrong. Every interior face must be shared by
/// exactly two tetrahedra, every other face must lie on the cube's boundary, and the volumes
/// (exact integer arithmetic) must add up to the cube.
std::string FaceMatchingProblem(const std::vector<Tetra>& tets);

/// Empty when TetGen accepts the mesh: it reconstructs the tetrahedra (tetgen -rn), and every
/// face it finds without a neighbour lies on the cube's boundary (a hanging vertex or a
/// mismatched face shows up as a neighbourless face inside the cube).
std::string TetGenProblem(const std::vector<Tetra>& tets);

}
}

#endif
