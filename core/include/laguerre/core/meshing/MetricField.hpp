#pragma once
/// @file
/// Metric fields: a symmetric positive definite matrix M(p) at each point p of a domain, the input of
/// anisotropic meshing (thesis Parts II and III). Built-in fields, analytic expressions, and values
/// interpolated on a background mesh; the distortion γ(p, q) and the bounded distortion radius of
/// thesis §2.4/§3.2 measured on a field.
///
/// Field specifications (the `--metric` option of `laguerre mesh`, and scenario files):
///   uniform:H1:H2[:THETA]             constant sizes H1 along THETA (degrees, default 0), H2 across
///   shock[:HMIN:HMAX:WIDTH:X0]        a shock layer along the vertical line x = X0 (default 0.5): size
///                                     across the layer h(x) = HMIN + (HMAX − HMIN)(1 − e^{−|x−X0|/WIDTH}),
///                                     HMAX along it (defaults 0.002, 0.1, 0.02)
///   thesis[:H:RATIO:WIDTH:Y0]         the field of thesis Fig. 3.4: stretched horizontally above y = Y0
///                                     and vertically below it, sizes H·√RATIO and H/√RATIO, the axes
///                                     exchanging continuously (log-linearly) across a band of half-width
///                                     WIDTH (defaults 0.05, 4, 0.1, 0.5)
///   expr:a=EXPR;b=EXPR;c=EXPR         the entries of M as expressions of x and y (muparser syntax)
///   sizes:h1=EXPR;h2=EXPR;theta=EXPR  sizes and direction (radians) as expressions of x and y
///   mesh:FILE.mesh[:FILE.sol]         per-vertex metrics on a background mesh (the .sol defaults to the
///                                     mesh path with .sol), interpolated linearly inside each triangle
/// A field that yields a matrix that is not SPD at some point throws FieldError at that point.
///
/// Fields of space (MetricField3, for 3D domains; `parse_metric_field3`):
///   uniform:H1:H2:H3                  constant sizes H1, H2, H3 along x, y, z
///   shock[:HMIN:HMAX:WIDTH:X0]        a shock layer around the plane x = X0: size across it h(|x − X0|)
///                                     with h as in 2D, HMAX along it (defaults 0.02, 0.2, 0.05, 0.5)
///   sphere[:HMIN:HMAX:WIDTH:R:CX:CY:CZ]  a shock layer around the sphere of centre C and radius R: size
///                                     h(|‖p − C‖ − R|) along the radius, HMAX tangentially, i.e.
///                                     M = I/HMAX² + (1/h² − 1/HMAX²)·nnᵀ with n the unit radial direction,
///                                     the anisotropy fading as (‖p − C‖/min(R, WIDTH))² near C so that
///                                     M is continuous (M = I/HMAX² at C; WIDTH alone when R = 0)
///                                     (defaults 0.02, 0.2, 0.05, 0.3, 0.5, 0.5, 0.5)
///   expr:xx=EXPR;xy=EXPR;xz=EXPR;yy=EXPR;yz=EXPR;zz=EXPR   the six entries as expressions of x, y, z
///   mesh:FILE.mesh[:FILE.sol]         per-vertex metrics (6 entries, or a size) on a background
///                                     tetrahedral mesh, interpolated linearly inside each tetrahedron

#include "laguerre/core/Error.hpp"
#include "laguerre/core/meshing/Metric.hpp"
#include "laguerre/core/meshing/Metric3.hpp"

#include <memory>
#include <stdexcept>
#include <string>

namespace laguerre::core {

/// A field specification that cannot be parsed, or a field that is not a metric where evaluated.
class FieldError : public InputError {
public:
  using InputError::InputError;
};

/// A metric field of the plane (or of a domain, for background-mesh fields).
class MetricField {
public:
  virtual ~MetricField() = default;
  /// The metric at (x, y). Throws FieldError if the value there is not SPD.
  virtual Metric at(double x, double y) const = 0;
  /// A one-line description (the specification it was built from, with defaults filled in).
  virtual std::string describe() const = 0;
};

/// A metric field of space (or of a domain, for background-mesh fields).
class MetricField3 {
public:
  virtual ~MetricField3() = default;
  /// The metric at (x, y, z). Throws FieldError if the value there is not SPD.
  virtual Metric3 at(double x, double y, double z) const = 0;
  /// A one-line description (the specification it was built from, with defaults filled in).
  virtual std::string describe() const = 0;
};

/// Parses a 3D field specification (see the file comment). Throws FieldError with the offending part,
/// or MeshInputError for a bad background mesh file.
std::unique_ptr<MetricField3> parse_metric_field3(const std::string& spec);

/// The constant field M of space.
std::unique_ptr<MetricField3> uniform_field3(const Metric3& m);

/// Parses a field specification (see the file comment). Throws FieldError with the offending part, or
/// MeshInputError for a bad background mesh file.
std::unique_ptr<MetricField> parse_metric_field(const std::string& spec);

/// The constant field M.
std::unique_ptr<MetricField> uniform_field(const Metric& m);

/// The shock layer of the file comment.
std::unique_ptr<MetricField> shock_layer_field(double h_min = 0.002, double h_max = 0.1, double width = 0.02,
                                               double x0 = 0.5);

/// The thesis Fig. 3.4 field of the file comment.
std::unique_ptr<MetricField> thesis_field(double h = 0.05, double ratio = 4, double width = 0.1, double y0 = 0.5);

/// γ(p, q) = γ(M(p), M(q)), thesis §3.2.
double distortion(const MetricField& field, double px, double py, double qx, double qy);

/// Numerical estimate of the bounded distortion radius bdr_LS(p, γ₀) (Labelle–Shewchuk, thesis §2.4):
/// the largest l ≤ `max_radius` such that every q with d_p(p, q) ≤ l has γ(p, q) ≤ γ₀. Samples
/// `rays` directions of the M(p)-unit circle and bisects the radius along each (`steps` bisections,
/// after a march of `rays` samples per ray to catch non-monotone distortion). An estimate, not a bound:
/// features narrower than the sampling are missed.
double bounded_distortion_radius(const MetricField& field, double px, double py, double gamma0, double max_radius,
                                 int rays = 32, int steps = 30);

}  // namespace laguerre::core
