//! Meshes from Wavefront OBJ files, the format every modelling tool writes.

use std::path::Path;

use super::TriangleMesh;
use crate::error::{Error, Result};

/// Reads every object of an OBJ file into one mesh; polygons are split into triangles, and points
/// and lines are dropped since they bound nothing. Materials are ignored (`mtllib` files are not
/// even opened): the scene assigns an object its optical material. Vertices without a usable normal
/// in the file get the area-weighted smooth normal, computed across vertices that the file split
/// only for texture seams.
///
/// Errors name `path`: a file that cannot be read, OBJ syntax tobj rejects, a file without
/// triangles, or non-finite coordinates.
pub fn load_obj(path: &Path) -> Result<TriangleMesh> {
    #[cfg(not(feature = "formats"))]
    return Err(Error::feature_off(path, "an OBJ mesh", "formats"));
    #[cfg(feature = "formats")]
    load_obj_file(path)
}

#[cfg(feature = "formats")]
fn load_obj_file(path: &Path) -> Result<TriangleMesh> {
    use std::fs::File;
    use std::io::BufReader;

    use glam::DVec3;

    let file = File::open(path).map_err(|e| Error::io(path, e))?;
    let (models, _materials) =
        tobj::load_obj_buf(&mut BufReader::new(file), &tobj::GPU_LOAD_OPTIONS, |_| {
            Ok(Default::default())
        })
        .map_err(|e| Error::bad_file(path, format!("malformed OBJ file: {e}")))?;

    let mut mesh = TriangleMesh::default();
    for model in &models {
        let m = &model.mesh;
        let count = m.positions.len() / 3;
        let base = mesh.positions.len() as u32;
        if mesh.positions.len() + count > u32::MAX as usize {
            return Err(Error::bad_file(path, "OBJ file has more than 2³² vertices"));
        }
        let vec3 = |c: &[f32]| DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2]));
        mesh.positions.extend(m.positions.chunks_exact(3).map(vec3));
        if m.normals.len() == m.positions.len() {
            // A zero normal in the file is as good as none; it is replaced below.
            mesh.normals.extend(
                m.normals
                    .chunks_exact(3)
                    .map(|n| vec3(n).try_normalize().unwrap_or(DVec3::ZERO)),
            );
        } else {
            mesh.normals.extend(std::iter::repeat_n(DVec3::ZERO, count));
        }
        mesh.indices.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
    }
    if mesh.indices.is_empty() {
        return Err(Error::bad_file(path, "OBJ file contains no triangles"));
    }
    // Checked before the normals are computed, so that the error is about the file's coordinates
    // rather than about normals derived from them.
    // tobj renumbers the vertices, so the error quotes the coordinates rather than an index.
    if let Some(p) = mesh.positions.iter().find(|p| !p.is_finite()) {
        return Err(Error::bad_file(
            path,
            format!("OBJ file has a vertex with a non-finite coordinate: {p}"),
        ));
    }
    super::fill_zero_normals(&mut mesh.normals, &mesh.positions, &mesh.indices);
    mesh.check()
        .map_err(|problem| Error::bad_file(path, format!("the mesh {problem}")))?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    /// A fresh directory under the system's temporary one, removed when dropped.
    struct TempDir(std::path::PathBuf);

    impl TempDir {
        fn new(name: &str) -> TempDir {
            let dir = std::env::temp_dir().join(format!(
                "caustics-mesh-{name}-{}-{:?}",
                std::process::id(),
                std::thread::current().id()
            ));
            std::fs::create_dir_all(&dir).unwrap();
            TempDir(dir)
        }

        fn write(&self, file: &str, text: &str) -> std::path::PathBuf {
            let path = self.0.join(file);
            std::fs::write(&path, text).unwrap();
            path
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    const TETRAHEDRON: &str = "\
# a unit right-angled tetrahedron, counter-clockwise from outside
mtllib missing.mtl
o tetrahedron
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
";

    #[test]
    fn tetrahedron_round_trip() {
        let dir = TempDir::new("round-trip");
        let mesh = load_obj(&dir.write("tetrahedron.obj", TETRAHEDRON)).unwrap();
        assert_eq!(mesh.indices.len(), 4);
        assert_eq!(mesh.positions.len(), 4);
        assert!((mesh.volume() - 1.0 / 6.0).abs() < 1e-12);
        assert!(mesh.is_closed());
        for n in &mesh.normals {
            assert!((n.length() - 1.0).abs() < 1e-12);
        }
        // The corner at the origin: the mean of the three axis-aligned faces, outward.
        assert!(mesh.normals[0].distance(-DVec3::ONE.normalize()) < 1e-12);
    }

    #[test]
    fn models_merge_and_file_normals_are_kept() {
        let text = "\
o first
v 0 0 0
v 1 0 0
v 0 1 0
vn 0 0 2
f 1//1 2//1 3//1
o second
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 4 5 6 7
";
        let dir = TempDir::new("merge");
        let mesh = load_obj(&dir.write("two.obj", text)).unwrap();
        assert_eq!(mesh.indices.len(), 3, "a triangle and a triangulated quad");
        assert_eq!(mesh.positions.len(), 7);
        // The file's normal, normalised, and computed ones where the file has none.
        assert!(mesh.normals.iter().all(|n| n.distance(DVec3::Z) < 1e-12));
        assert!(mesh.indices.iter().flatten().all(|&i| i < 7));
        assert!((mesh.area() - 1.5).abs() < 1e-12);
    }

    #[test]
    fn errors_name_the_file() {
        let dir = TempDir::new("errors");
        let cases = [
            (
                "syntax.obj",
                "v 1.0 abc 2.0\nv 0 0 0\nv 1 1 1\nf 1 2 3\n",
                "malformed",
            ),
            (
                "index.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
                "malformed",
            ),
            ("empty.obj", "# nothing here\n", "no triangles"),
            ("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n", "no triangles"),
            (
                "huge.obj",
                "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n",
                "non-finite",
            ),
        ];
        for (file, text, problem) in cases {
            let path = dir.write(file, text);
            let e = load_obj(&path).unwrap_err().to_string();
            assert!(e.contains(&path.display().to_string()), "{e}");
            assert!(e.contains(problem), "{file}: {e}");
        }
        let missing = dir.0.join("missing.obj");
        let e = load_obj(&missing).unwrap_err();
        assert!(matches!(e, Error::Io { .. }));
        assert!(e.to_string().contains(&missing.display().to_string()));
    }
}
