//! Tetrahedral meshes from TetGen's `.node` and `.ele` files.
//!
//! No maintained crate parses these files, so this module does, following
//! TetGen's manual:
//!
//! ```text
//! .node   <points> 3 <attributes> <boundary markers 0|1>
//!         <index> <x> <y> <z> [attributes…] [marker]        one line per point
//! .ele    <tets> <4|10> <region attribute 0|1>
//!         <index> <n1> <n2> <n3> <n4> [6 more nodes] [attribute]
//! ```
//!
//! `#` starts a comment; blank lines are skipped. Points are numbered
//! consecutively from 0 or 1 (the first point decides) and tets name them by
//! those numbers; of a 10-node tet the 4 corners are kept. Every problem is
//! reported with its file and line.

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use hooke_core::Vec3;

use crate::error::SceneError;
use crate::mesh::TetMesh;

/// Reads `<base>.node` and `<base>.ele`.
///
/// ```
/// let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
/// let cube = hooke_scenes::tetgen::load(dir.join("tests/data/cube.1"))?;
/// assert_eq!((cube.vertices.len(), cube.tets.len()), (8, 5));
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
///
/// # Errors
/// [`SceneError::Io`] if a file cannot be read, [`SceneError::Parse`]
/// naming the file and line of the first malformed entry.
pub fn load(base: impl AsRef<Path>) -> Result<TetMesh, SceneError> {
    let with = |extension: &str| {
        let mut name = OsString::from(base.as_ref());
        name.push(extension);
        PathBuf::from(name)
    };
    let (node_path, ele_path) = (with(".node"), with(".ele"));
    let read = |path: &Path| {
        std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_owned(),
            source,
        })
    };
    read_mesh(&read(&node_path)?, &node_path, &read(&ele_path)?, &ele_path)
}

/// Parses the text of a `.node` and an `.ele` file (named `<node>` and
/// `<ele>` in errors).
///
/// ```
/// let node = "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n";
/// let ele = "1 4 0\n1 1 2 3 4\n";
/// let mesh = hooke_scenes::tetgen::parse(node, ele)?;
/// assert_eq!(mesh.tets, [[0, 1, 2, 3]]);
/// # Ok::<(), hooke_scenes::SceneError>(())
/// ```
///
/// # Errors
/// [`SceneError::Parse`] naming the file and line of the first malformed
/// entry.
pub fn parse(node: &str, ele: &str) -> Result<TetMesh, SceneError> {
    read_mesh(node, Path::new("<node>"), ele, Path::new("<ele>"))
}

fn read_mesh(
    node: &str,
    node_path: &Path,
    ele: &str,
    ele_path: &Path,
) -> Result<TetMesh, SceneError> {
    let mut nodes = Lines::new(node, node_path);
    let (line, header) = nodes.next_entry("the header `<points> 3 <attributes> <markers>`")?;
    let [points, dimension, attributes, markers] = nodes.numbers::<4>(line, &header, 4)?;
    if dimension != 3 {
        return Err(nodes.error(line, format!("dimension must be 3, got {dimension}")));
    }
    if markers > 1 {
        return Err(nodes.error(
            line,
            format!("boundary markers must be 0 or 1, got {markers}"),
        ));
    }
    let mut vertices = Vec::new();
    let mut base = 0;
    for k in 0..points {
        let (line, fields) = nodes.next_entry("a point")?;
        let [index] =
            nodes.numbers::<1>(line, &fields, 4usize.saturating_add(attributes) + markers)?;
        if k == 0 {
            base = index.min(1);
        }
        if index != base + k {
            return Err(nodes.error(line, format!("point number {index}, expected {}", base + k)));
        }
        let mut xyz = [0.0; 3];
        for (c, field) in xyz.iter_mut().zip(&fields[1..4]) {
            *c = field
                .parse::<f64>()
                .ok()
                .filter(|c| c.is_finite())
                .ok_or_else(|| {
                    nodes.error(line, format!("`{field}` is not a finite coordinate"))
                })?;
        }
        vertices.push(Vec3::from(xyz));
    }
    nodes.finish(points, "points")?;

    let mut eles = Lines::new(ele, ele_path);
    let (line, header) = eles.next_entry("the header `<tets> <4|10> <attributes>`")?;
    let [count, corners, region] = eles.numbers::<3>(line, &header, 3)?;
    if corners != 4 && corners != 10 {
        return Err(eles.error(
            line,
            format!("nodes per tet must be 4 or 10, got {corners}"),
        ));
    }
    if region > 1 {
        return Err(eles.error(
            line,
            format!("region attribute must be 0 or 1, got {region}"),
        ));
    }
    let mut tets = Vec::new();
    for _ in 0..count {
        let (line, fields) = eles.next_entry("a tet")?;
        let numbers = eles.numbers::<5>(line, &fields, 1 + corners + region)?;
        let mut tet = [0; 4];
        for (corner, &point) in tet.iter_mut().zip(&numbers[1..]) {
            *corner = point
                .checked_sub(base)
                .filter(|&p| p < points)
                .ok_or_else(|| {
                    eles.error(
                        line,
                        format!(
                            "point {point} is not in the .node file ({base}..{})",
                            base + points
                        ),
                    )
                })?;
        }
        tets.push(tet);
    }
    eles.finish(count, "tets")?;
    Ok(TetMesh { vertices, tets })
}

/// The entries of a TetGen file: non-blank lines with comments removed.
struct Lines<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    path: &'a Path,
    last: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, path: &'a Path) -> Self {
        Self {
            lines: text.lines().enumerate(),
            path,
            last: 0,
        }
    }

    fn error(&self, line: usize, message: String) -> SceneError {
        SceneError::Parse {
            file: self.path.to_owned(),
            line,
            message,
        }
    }

    /// The next entry's line number and fields.
    fn next_entry(&mut self, what: &str) -> Result<(usize, Vec<&'a str>), SceneError> {
        for (n, text) in self.lines.by_ref() {
            self.last = n + 1;
            let content = text.split('#').next().unwrap_or_default();
            let fields: Vec<&str> = content.split_whitespace().collect();
            if !fields.is_empty() {
                return Ok((n + 1, fields));
            }
        }
        Err(self.error(self.last, format!("file ends where {what} was expected")))
    }

    /// Checks there are `expected` fields and parses the first `N` as
    /// non-negative integers.
    fn numbers<const N: usize>(
        &self,
        line: usize,
        fields: &[&str],
        expected: usize,
    ) -> Result<[usize; N], SceneError> {
        if fields.len() != expected {
            return Err(self.error(
                line,
                format!("expected {expected} fields, found {}", fields.len()),
            ));
        }
        let mut numbers = [0; N];
        for (number, field) in numbers.iter_mut().zip(fields) {
            *number = field.parse().map_err(|_| {
                self.error(line, format!("`{field}` is not a non-negative integer"))
            })?;
        }
        Ok(numbers)
    }

    /// Checks nothing but comments follow the `count` entries read.
    fn finish(&mut self, count: usize, what: &str) -> Result<(), SceneError> {
        match self.next_entry("") {
            Ok((line, _)) => Err(self.error(
                line,
                format!("more entries than the {count} {what} the header declares"),
            )),
            Err(_) => Ok(()),
        }
    }
}
