#pragma once
/// Element kernels of linear (P1) tetrahedra and triangles: pure functions on fixed-size Eigen types,
/// with no knowledge of meshes, assembly or time stepping (STYLE.md rule 3). Lengths are in whatever unit
/// the caller uses (forensim: mm); coefficients multiply the integrals as stated.
///
/// Conventions: a tet's corners are p0..p3, positively oriented ((p1-p0).dot((p2-p0).cross(p3-p0)) > 0).
/// Shape gradients are the columns of a 3x4 matrix G (column i = grad N_i). 12-vectors stack the corners'
/// xyz (x0 y0 z0 x1 ...). Voigt strain order is (xx, yy, zz, xy, yz, zx) with engineering shears (2 eps_xy).
/// Sources: Frerichs et al. 2021 (mummification by desiccation), eqs. 11-14 (diffusion) and 24-30
/// (elasticity); Mueller and Gross 2004, "Interactive virtual materials" (element-warped stiffness).

#include <array>

#include "core/types.hpp"

namespace forensim {

using TetCorners = std::array<Vec3, 4>;
using Mat34 = Eigen::Matrix<double, 3, 4>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat6x12 = Eigen::Matrix<double, 6, 12>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

/// Signed volume of the tet (positive when positively oriented).
double tet_volume(const TetCorners& p);

/// Gradients of the four linear shape functions N_i (columns), constant over the tet. `volume` receives
/// the signed volume when not null. Throws NumericError for a degenerate tet (zero volume).
Mat34 tet_shape_gradients(const TetCorners& p, double* volume = nullptr);

/// Diffusion stiffness K_e (eq. 11) times a constant coefficient k: K_ij = k V grad N_i . grad N_j.
/// Symmetric positive semi-definite, rows sum to zero. `grads` from tet_shape_gradients, `volume` > 0.
Mat4 tet_diffusion_stiffness(const Mat34& grads, double volume, double k);

/// Consistent mass M_e (eq. 12) for a constant coefficient c: M_ij = c V (1 + delta_ij) / 20.
Mat4 tet_consistent_mass(double volume, double c);

/// Row-sum lumped mass: c V / 4 per corner.
Vec4 tet_lumped_mass(double volume, double c);

/// Robin boundary matrix H_f (eq. 13) on triangle abc for a constant coefficient h:
/// H_ij = h A (1 + delta_ij) / 12.
Mat3 triangle_robin_matrix(const Vec3& a, const Vec3& b, const Vec3& c, double h);

/// Robin boundary load f_f (eq. 14) on triangle abc: f_i = h u_ambient A / 3.
Vec3 triangle_robin_load(const Vec3& a, const Vec3& b, const Vec3& c, double h, double ambient);

/// Lame's first parameter lambda and shear modulus mu from Young's modulus E and Poisson's ratio nu
/// (-1 < nu < 0.5), in the unit of E.
Vec2 lame_parameters(double youngs_modulus, double poisson_ratio);

/// Isotropic elasticity matrix C (6x6, Voigt, engineering shears) from E and nu (eq. 17's E).
Mat6 isotropic_elasticity(double youngs_modulus, double poisson_ratio);

/// Strain-displacement matrix B (6x12): eps = B u for corner displacements u (eq. 18 linearised).
Mat6x12 tet_strain_matrix(const Mat34& grads);

/// Linear-elastic stiffness K_e = V B^T C B (12x12, eq. 26) in the unit of E times length.
Mat12 tet_linear_stiffness(const Mat34& grads, double volume, double youngs_modulus, double poisson_ratio);

/// Inverse of the rest edge matrix Dm = [p1-p0, p2-p0, p3-p0] (3x3).
Mat3 tet_rest_edge_inverse(const TetCorners& rest);

/// Deformation gradient F = Ds Dm^-1 of the deformed corners `x` (Ds = [x1-x0, x2-x0, x3-x0]).
Mat3 tet_deformation_gradient(const TetCorners& x, const Mat3& rest_edge_inverse);

/// Rotation R of the polar decomposition F = R S (Mueller and Gross 2004 extract R to warp the stiffness).
/// Computed by SVD; for inverted elements (det F <= 0) the singular vector of the smallest singular value
/// is flipped so that R stays a proper rotation (det R = +1).
Mat3 rotation_from_deformation(const Mat3& deformation_gradient);

/// The same rotation by Higham's Newton iteration (Higham 1986, "Computing the polar decomposition with
/// applications"): X <- (zeta X + X^-T / zeta) / 2 from X = F, with the Frobenius-norm scaling
/// zeta = (|X^-1|_F / |X|_F)^(1/2) while X is far from orthogonal. The error is squared each iteration
/// (e_{k+1} ~ e_k^2 / 2), so it stops once a step changes X by less than 1e-8 (the next error ~1e-16):
/// 2-4 iterations for the stretches of drying tissue, a fraction of the cost of an SVD. A function of F
/// alone, with no warm start, so that results never depend on what was computed before (a run resumed from
/// a checkpoint repeats the same arithmetic). Falls back to rotation_from_deformation for det F <= 0
/// (inverted) and when the iteration does not settle.
Mat3 polar_rotation(const Mat3& deformation_gradient);

/// polar_rotation of each of `count` deformation gradients, bit for bit the same results, computed in groups
/// of lanes in SIMD packets (Eigen's; SSE2: 4 packets of 2), each matrix's iteration stopping on its own:
/// about 1.6 times faster per matrix than one call each (145000 drying-like gradients, one core), which
/// is latency-bound on its divisions and square roots. `rotations` must not overlap `deformation_gradients`.
void polar_rotations(const Mat3* deformation_gradients, Mat3* rotations, std::size_t count);

/// Gradient sum_i v_i grad N_i^T (3x3) of the linear field with corner values v (columns of `corners`, 3x4):
/// the deformation gradient F for corner positions, grad u for corner displacements.
inline Mat3 tet_field_gradient(const Mat34& grads, const Mat34& corners) {
  return corners * grads.transpose();
}

/// Stress of the corotated linear model with isotropic eigenstrain s I, as a symmetric 3x3 tensor in the
/// unrotated frame: sigma = lambda tr(e) I + 2 mu e, e = sym(R^T G) - (1 + s) I, G = F (eq. 30's
/// C (eps - eps0) with C isotropic). With s = -1 and G a displacement gradient it is the linear stress of
/// R^T G, the product of the warped stiffness. lambda, mu: Lame parameters (lame_parameters).
inline Mat3 corotated_strain(const Mat3& r, const Mat3& g, double s);
inline Mat3 isotropic_stress(const Mat3& e, double lambda, double mu);
inline Mat3 corotated_stress(const Mat3& r, const Mat3& g, double lambda, double mu, double s) {
  return isotropic_stress(corotated_strain(r, g, s), lambda, mu);
}

/// The strain of corotated_stress, e = sym(R^T G) - (1 + s) I (the energy density is e : sigma / 2).
inline Mat3 corotated_strain(const Mat3& r, const Mat3& g, double s) {
  const Mat3 rg = r.transpose() * g;
  Mat3 e = 0.5 * (rg + rg.transpose());
  e.diagonal().array() -= 1.0 + s;
  return e;
}

/// sigma = lambda tr(e) I + 2 mu e (isotropic linear elasticity; lambda, mu: Lame parameters).
inline Mat3 isotropic_stress(const Mat3& e, double lambda, double mu) {
  Mat3 sigma = (2.0 * mu) * e;
  sigma.diagonal().array() += lambda * e.trace();
  return sigma;
}

/// Applies a 3x3 matrix to each of the four xyz blocks of a 12-vector.
Vec12 rotate_blocks(const Mat3& r, const Vec12& v);

/// Warped stiffness R K R^T (blockwise R), the tangent used by the implicit step.
Mat12 rotate_stiffness(const Mat3& r, const Mat12& k);

/// Corner forces of an isotropic eigenstrain eps0 = s I in the unrotated frame: V B^T C eps0 (eq. 30
/// without R). A negative s (shrinkage) pulls the corners towards the centroid when unconstrained.
Vec12 tet_eigenstrain_force(const Mat34& grads, double volume, const Mat6& elasticity, double s);

/// Element-warped elastic force on the corners (Mueller and Gross 2004 with eq. 30):
/// f = -R (K (R^T x - x0) - f_eig), where f_eig = tet_eigenstrain_force. x, x0: 12-vectors.
/// This is exactly minus the gradient of tet_corotational_energy when R is the polar rotation of F.
Vec12 tet_corotational_force(const Mat12& k, const Mat3& r, const Vec12& x, const Vec12& x0, const Vec12& f_eig);

/// Strain energy of the corotated linear model with an isotropic eigenstrain s I:
/// V/2 (eps - eps0)^T C (eps - eps0), eps = Voigt(S - I) where F = R S (polar). For derivative checks.
double tet_corotational_energy(const TetCorners& x, const Mat3& rest_edge_inverse, double volume,
                               const Mat6& elasticity, double s);

/// Compression barrier of a shrinking tet (beyond eqs. 28-31). The corotated linear model alone lets a tet that
/// its neighbours squeeze sideways shrink through zero volume and turn over (its energy stays finite there), which
/// drying tissue cannot do: the dry solid keeps a volume. The barrier's energy per rest volume is
///   psi(F) = kappa b(r),  r = det F / J_t,  J_t = (1 + s)^3 (the volume ratio the eigenstrain s aims at),
///   b(r) = -(r - r0)^2 ln(r / r0) for 0 < r < r0, 0 for r >= r0, +infinity for r <= 0
/// (the barrier of Li et al. 2020, "Incremental potential contact"). b is C2 at r0 (b = b' = b'' = 0), so every
/// tet that keeps at least r0 of its target volume feels nothing. kappa: a modulus (the solver uses the bulk
/// modulus lambda + 2 mu / 3). r0 <= 0 or kappa <= 0: no barrier (returns 0). `gradient`, when not null,
/// receives d psi / dF = kappa b'(r) / J_t cof(F) (zero outside the barrier's range).
double tet_volume_barrier(const Mat3& deformation_gradient, double s, double kappa, double r0, Mat3* gradient);

/// Stacks four corners into a 12-vector.
Vec12 stack_corners(const TetCorners& p);

}  // namespace forensim
