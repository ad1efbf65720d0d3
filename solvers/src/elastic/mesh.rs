//! Mapped quadrilateral meshes of the shaft and the housing of a journal bearing.
//!
//! Both bodies are meshed along rays θ_k = 2πk/n_θ (k = 0 … n_θ − 1) from the film surface
//! (journal surface r = R of the shaft, bore r = R of the housing) to the other boundary, with
//! n_r element layers spaced geometrically along each ray,
//!
//! ```text
//!   r_j(θ) = r_a · (r_b(θ)/r_a)^(j/n_r),   j = 0 … n_r
//! ```
//!
//! (on an annulus this is the conformal map of a rectangle: with n_r ≈ ln(r_b/r_a)/Δθ the
//! elements are nearly square everywhere, small near the film where the pressure varies fast).
//! The film-surface nodes are the same n_θ angles on both bodies, so that the gap change of
//! node k is the difference of the two bodies' radial displacements at θ_k.
//!
//! Shaft: an annulus from a central hole r_h to R, every hole node held radially and the node
//! at θ = 0 also tangentially (the paper's support, \[Benasciutti2012\] Fig. 5 and its text, plus the one
//! constraint that removes the rigid rotation, which radial supports on a circle leave free;
//! the film pressure is normal to the surface and its discrete resultant moment is zero — see
//! [`super::ElasticBody::surface_load`] — so that support carries no load).
//! Housing: from the bore R out to a square of half-width H (the paper's "external edges
//! constrained", fixed there) or, for the closed-form checks, to a circle.

use std::f64::consts::PI;

/// Which displacement components of a node are held at zero, in the node's polar frame
/// (e_r = (cos θ, sin θ), e_θ = (−sin θ, cos θ), θ the node's polar angle).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Support {
    /// u_r = 0.
    Radial,
    /// u_θ = 0.
    Tangential,
    /// u = 0.
    Fixed,
}

/// Where the film is, seen from the body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FluidSide {
    /// The film surrounds the body (the shaft's outer surface).
    Outside,
    /// The film fills the body's bore (the housing).
    Inside,
}

/// Outer boundary of a housing mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HousingShape {
    /// A square block of half-width H (side 2H), centred on the bore.
    Square { half_width: f64 },
    /// A circle of radius R_o.
    Circle { radius: f64 },
}

/// A mesh of bilinear quadrilaterals with its film surface and supports.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Node coordinates (x, y), m.
    pub nodes: Vec<[f64; 2]>,
    /// Elements: four node indices, anticlockwise.
    pub elements: Vec<[usize; 4]>,
    /// Film-surface nodes in θ order, node k at θ_k = 2πk/n (a closed ring).
    pub surface: Vec<usize>,
    /// Where the film is, seen from the body.
    pub fluid: FluidSide,
    /// Supported nodes.
    pub supports: Vec<(usize, Support)>,
    /// n_r + 1 nodes along each ray: node (k, j) is `k · (n_r + 1) + j`, j = 0 on the film
    /// surface.
    pub nodes_per_ray: usize,
}

/// Element layers that make the elements of an annulus r_a … r_b nearly square with n_θ
/// around: ⌈ln(r_b/r_a) / Δθ⌉ (at least 1).
pub fn square_layers(r_a: f64, r_b: f64, n_theta: usize) -> usize {
    let d_theta = 2.0 * PI / n_theta as f64;
    (((r_b / r_a).ln().abs() / d_theta).ceil() as usize).max(1)
}

impl Mesh {
    /// The common ray mesh: rays at θ_k from the film surface radius `r_surface` to
    /// `r_other(θ)`, n_r layers geometrically spaced; surface = the j = 0 ring.
    fn rays(
        r_surface: f64,
        r_other: impl Fn(f64) -> f64,
        n_theta: usize,
        n_r: usize,
        fluid: FluidSide,
    ) -> Self {
        let m = n_r + 1;
        let mut nodes = Vec::with_capacity(n_theta * m);
        for k in 0..n_theta {
            let th = 2.0 * PI * k as f64 / n_theta as f64;
            let ratio = r_other(th) / r_surface;
            for j in 0..m {
                let r = if j == 0 {
                    r_surface
                } else {
                    r_surface * ratio.powf(j as f64 / n_r as f64)
                };
                nodes.push([r * th.cos(), r * th.sin()]);
            }
        }
        let mut elements = Vec::with_capacity(n_theta * n_r);
        for k in 0..n_theta {
            let kn = (k + 1) % n_theta;
            for j in 0..n_r {
                // Anticlockwise: the inner radius first, along +r, then along +θ.
                let (a, b, c, d) = (k * m + j, k * m + j + 1, kn * m + j + 1, kn * m + j);
                elements.push(match fluid {
                    // j grows inwards on the shaft: (inner, outer) = (j + 1, j).
                    FluidSide::Outside => [b, a, d, c],
                    FluidSide::Inside => [a, b, c, d],
                });
            }
        }
        Self {
            nodes,
            elements,
            surface: (0..n_theta).map(|k| k * m).collect(),
            fluid,
            supports: Vec::new(),
            nodes_per_ray: m,
        }
    }

    /// Nodes of the ring j (j = 0: the film surface; j = n_r: the other boundary).
    pub fn ring(&self, j: usize) -> Vec<usize> {
        let n = self.nodes.len() / self.nodes_per_ray;
        (0..n).map(|k| k * self.nodes_per_ray + j).collect()
    }

    /// The shaft: an annulus from the hole `hole_radius` to the journal surface `radius`, the
    /// hole held radially and its node at θ = 0 also tangentially (module docs).
    pub fn shaft(hole_radius: f64, radius: f64, n_theta: usize, n_r: usize) -> Self {
        let mut mesh = Self::rays(radius, |_| hole_radius, n_theta, n_r, FluidSide::Outside);
        let hole = mesh.ring(n_r);
        mesh.supports = hole
            .iter()
            .enumerate()
            .map(|(k, &node)| {
                (
                    node,
                    if k == 0 {
                        Support::Fixed
                    } else {
                        Support::Radial
                    },
                )
            })
            .collect();
        mesh
    }

    /// The housing: from the bore `bore_radius` out to `shape`, fixed on that outer boundary.
    pub fn housing(bore_radius: f64, shape: HousingShape, n_theta: usize, n_r: usize) -> Self {
        let outer = move |th: f64| match shape {
            HousingShape::Square { half_width } => half_width / th.cos().abs().max(th.sin().abs()),
            HousingShape::Circle { radius } => radius,
        };
        let mut mesh = Self::rays(bore_radius, outer, n_theta, n_r, FluidSide::Inside);
        mesh.supports = mesh
            .ring(n_r)
            .into_iter()
            .map(|n| (n, Support::Fixed))
            .collect();
        mesh
    }

    /// An annulus r_in … r_out without supports, the film surface on the `fluid` side (inner
    /// ring for [`FluidSide::Inside`], outer for [`FluidSide::Outside`]).
    pub fn annulus(r_in: f64, r_out: f64, fluid: FluidSide, n_theta: usize, n_r: usize) -> Self {
        match fluid {
            FluidSide::Inside => Self::rays(r_in, |_| r_out, n_theta, n_r, fluid),
            FluidSide::Outside => Self::rays(r_out, |_| r_in, n_theta, n_r, fluid),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(mesh: &Mesh) -> f64 {
        mesh.elements
            .iter()
            .map(|e| {
                0.5 * (0..4)
                    .map(|a| {
                        let (p, q) = (mesh.nodes[e[a]], mesh.nodes[e[(a + 1) % 4]]);
                        p[0] * q[1] - q[0] * p[1]
                    })
                    .sum::<f64>()
            })
            .sum()
    }

    /// Every element is anticlockwise (positive area) and the elements tile the body: the
    /// summed area is the polygonal annulus / square-minus-polygon area.
    #[test]
    fn meshes_tile_their_bodies() {
        let n = 48;
        let polygon = |r: f64| 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin();
        let shaft = Mesh::shaft(0.1, 0.25, n, 6);
        assert!((area(&shaft) / (polygon(0.25) - polygon(0.1)) - 1.0).abs() < 1e-12);
        // n a multiple of 8: the square's corners are nodes, so its area is exact.
        let housing = Mesh::housing(0.25, HousingShape::Square { half_width: 0.5 }, n, 7);
        assert!((area(&housing) / (1.0 - polygon(0.25)) - 1.0).abs() < 1e-12);
        for mesh in [&shaft, &housing] {
            for e in &mesh.elements {
                let a: f64 = 0.5
                    * (0..4)
                        .map(|a| {
                            let (p, q) = (mesh.nodes[e[a]], mesh.nodes[e[(a + 1) % 4]]);
                            p[0] * q[1] - q[0] * p[1]
                        })
                        .sum::<f64>();
                assert!(a > 0.0);
            }
            for (k, &s) in mesh.surface.iter().enumerate() {
                let [x, y] = mesh.nodes[s];
                let th = y.atan2(x).rem_euclid(2.0 * PI);
                let expect = 2.0 * PI * k as f64 / n as f64;
                assert!((th - expect).abs() < 1e-12 || (th - expect).abs() > 2.0 * PI - 1e-12);
            }
        }
        assert_eq!(shaft.supports.len(), n);
        assert_eq!(housing.supports.len(), n);
        assert_eq!(square_layers(0.1, 0.25, 240), 35);
    }
}
