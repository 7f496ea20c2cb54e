//! Analytic shapes with exact normals, centred on the origin.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::TriangleMesh;

/// A UV sphere: `segments` meridians and `rings` bands of latitude, one shared vertex at each pole
/// and no seam vertices, so the mesh is closed and a ray cannot slip between two triangles. Normals
/// are the exact radial directions rather than facet averages, so refraction sees the true sphere.
/// `segments` is raised to at least 3 and `rings` to at least 2, the fewest that enclose a volume.
pub fn sphere(radius: f64, segments: u32, rings: u32) -> TriangleMesh {
    let segments = segments.max(3);
    let rings = rings.max(2);
    let mut normals = vec![DVec3::Z];
    for r in 1..rings {
        let theta = PI * f64::from(r) / f64::from(rings);
        for s in 0..segments {
            let phi = TAU * f64::from(s) / f64::from(segments);
            normals.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ));
        }
    }
    normals.push(DVec3::NEG_Z);
    let south = normals.len() as u32 - 1;
    // Vertex `s` of ring `r` (1-based from the north pole); `s` wraps around the seam.
    let at = |r: u32, s: u32| 1 + (r - 1) * segments + s % segments;

    let mut indices = Vec::with_capacity(2 * (segments * (rings - 1)) as usize);
    for s in 0..segments {
        indices.push([0, at(1, s), at(1, s + 1)]);
    }
    for r in 1..rings - 1 {
        for s in 0..segments {
            let [a, b, c, d] = [at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1)];
            indices.push([a, b, c]);
            indices.push([a, c, d]);
        }
    }
    for s in 0..segments {
        indices.push([south, at(rings - 1, s + 1), at(rings - 1, s)]);
    }
    TriangleMesh {
        positions: normals.iter().map(|&n| radius * n).collect(),
        normals,
        indices,
    }
}

/// A box from `-half_extents` to `half_extents`. Each face has its own four vertices so that its
/// normal is the face's, not an average across the edge that would round the box off in shading.
pub fn cuboid(half_extents: DVec3) -> TriangleMesh {
    // Each face as (outward normal, u, v) with u × v = normal, so the quad (−u−v, u−v, u+v, −u+v)
    // is counter-clockwise seen from outside.
    const FACES: [[DVec3; 3]; 6] = [
        [DVec3::X, DVec3::Y, DVec3::Z],
        [DVec3::NEG_X, DVec3::Z, DVec3::Y],
        [DVec3::Y, DVec3::Z, DVec3::X],
        [DVec3::NEG_Y, DVec3::X, DVec3::Z],
        [DVec3::Z, DVec3::X, DVec3::Y],
        [DVec3::NEG_Z, DVec3::Y, DVec3::X],
    ];
    let mut mesh = TriangleMesh::default();
    for [n, u, v] in FACES {
        let base = mesh.positions.len() as u32;
        for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            mesh.positions.push((n + su * u + sv * v) * half_extents);
            mesh.normals.push(n);
        }
        mesh.indices.push([base, base + 1, base + 2]);
        mesh.indices.push([base, base + 2, base + 3]);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_converges_and_is_closed() {
        let r = 1.7;
        let s = sphere(r, 64, 32);
        s.validate("sphere").unwrap();
        assert!(s.is_closed());
        assert_eq!(s.positions.len(), 2 + 64 * 31);
        assert_eq!(s.indices.len(), 2 * 64 * 31);
        let area = 4.0 * PI * r * r;
        let volume = 4.0 / 3.0 * PI * r * r * r;
        assert!((s.area() / area - 1.0).abs() < 0.01, "{}", s.area() / area);
        assert!(
            (s.volume() / volume - 1.0).abs() < 0.01,
            "{}",
            s.volume() / volume
        );
        // Inscribed, so it converges from below, and a finer sphere is closer.
        let fine = sphere(r, 256, 128);
        assert!(s.volume() < fine.volume() && fine.volume() < volume);
        assert!((fine.volume() / volume - 1.0).abs() < 1e-3);
        let (lo, hi) = s.bounds();
        assert!((hi.z - r).abs() < 1e-12 && (lo.z + r).abs() < 1e-12);
    }

    #[test]
    fn sphere_winding_agrees_with_normals() {
        let s = sphere(2.0, 7, 3);
        assert!(s.is_closed());
        for tri in &s.indices {
            let [a, b, c] = tri.map(|i| s.positions[i as usize]);
            let face = (b - a).cross(c - a);
            assert!(face.dot(a + b + c) > 0.0, "triangle {tri:?} faces inwards");
        }
        // The smallest request still encloses a volume.
        let tiny = sphere(1.0, 0, 0);
        assert!(tiny.is_closed() && tiny.volume() > 0.0);
    }

    #[test]
    fn cuboid_is_exact_and_closed() {
        let h = DVec3::new(0.5, 1.5, 2.0);
        let c = cuboid(h);
        c.validate("cuboid").unwrap();
        assert_eq!((c.positions.len(), c.indices.len()), (24, 12));
        assert!(c.is_closed());
        assert!((c.volume() - 12.0).abs() < 1e-12);
        assert!((c.area() - 2.0 * (3.0 + 4.0 + 12.0)).abs() < 1e-12);
        assert_eq!(c.bounds(), (-h, h));
        for tri in &c.indices {
            let [a, b, cc] = tri.map(|i| c.positions[i as usize]);
            let face = (b - a).cross(cc - a).normalize();
            for &i in tri {
                assert!(face.distance(c.normals[i as usize]) < 1e-15);
            }
        }
    }
}
