//! The canonical shapes of Modular Radiance Transfer's 2D cube dictionary (Loos 2015 §3.5.1,
//! Fig. 4.1): a unit cube whose floor and ceiling are always present and whose four side walls
//! may be open, six entries up to rotation about the up axis. Each present face carries
//! `res x res` texels at their centres; this module lays them out in one sample vector and maps a
//! point on a face back to the four texels a bilinear lookup reads.
//!
//! Frame: the cube is [0, 1]^3, y up. Face normals point into the block (the surfaces a gather
//! sees from inside).

use glam::Vec3;

/// One face of the unit cube.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Face {
    /// x = 0.
    NegX,
    /// x = 1.
    PosX,
    /// y = 0 (floor).
    NegY,
    /// y = 1 (ceiling).
    PosY,
    /// z = 0.
    NegZ,
    /// z = 1.
    PosZ,
}

impl Face {
    /// Every face, in layout order.
    pub const ALL: [Face; 6] = [Face::NegX, Face::PosX, Face::NegY, Face::PosY, Face::NegZ, Face::PosZ];

    /// The axis the face is perpendicular to (0 x, 1 y, 2 z).
    pub fn axis(self) -> usize {
        self as usize / 2
    }

    /// Whether the face lies at coordinate 1 on its axis (else 0).
    pub fn positive(self) -> bool {
        self as usize % 2 == 1
    }

    /// The face at coordinate `positive` on `axis`.
    pub fn from_axis(axis: usize, positive: bool) -> Face {
        Face::ALL[axis * 2 + usize::from(positive)]
    }

    /// The unit normal pointing into the cube.
    pub fn inward_normal(self) -> Vec3 {
        let mut n = Vec3::ZERO;
        n[self.axis()] = if self.positive() { -1.0 } else { 1.0 };
        n
    }

    /// The face's two in-plane axes (s, t): for side walls (horizontal, y), for the floor and
    /// ceiling (x, z).
    pub fn plane_axes(self) -> (usize, usize) {
        match self.axis() {
            0 => (2, 1),
            1 => (0, 2),
            _ => (0, 1),
        }
    }

    /// The point of the face at in-plane coordinates (s, t) in [0, 1]^2.
    pub fn point(self, s: f32, t: f32) -> Vec3 {
        let (a, b) = self.plane_axes();
        let mut p = Vec3::ZERO;
        p[self.axis()] = if self.positive() { 1.0 } else { 0.0 };
        p[a] = s;
        p[b] = t;
        p
    }

    /// The face on the other side of the cube.
    pub fn opposite(self) -> Face {
        Face::from_axis(self.axis(), !self.positive())
    }

    /// The face rotated a quarter turn about +y, counter-clockwise seen from above (+x -> -z).
    pub fn rotated_about_up(self) -> Face {
        match self {
            Face::PosX => Face::NegZ,
            Face::NegZ => Face::NegX,
            Face::NegX => Face::PosZ,
            Face::PosZ => Face::PosX,
            other => other,
        }
    }

    /// The face after `q` quarter turns about +y (each as [`Self::rotated_about_up`]).
    pub fn turned(self, q: u8) -> Face {
        (0..q % 4).fold(self, |f, _| f.rotated_about_up())
    }
}

/// The six dictionary entries (Loos 2015 §3.5.1), each with its canonical open side walls.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    /// No side open.
    Closed,
    /// One side open (+z).
    DeadEnd,
    /// Two opposite sides open (-z, +z).
    Corridor,
    /// Two adjacent sides open (+x, +z).
    Corner,
    /// Three sides open (-x, +x, +z).
    TJunction,
    /// All four sides open.
    Crossroads,
}

impl Shape {
    /// Every entry, in dictionary order.
    pub const ALL: [Shape; 6] =
        [Shape::Closed, Shape::DeadEnd, Shape::Corridor, Shape::Corner, Shape::TJunction, Shape::Crossroads];

    /// Its name in files and the inspector.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Closed => "closed",
            Shape::DeadEnd => "dead end",
            Shape::Corridor => "corridor",
            Shape::Corner => "corner",
            Shape::TJunction => "T junction",
            Shape::Crossroads => "crossroads",
        }
    }

    /// The open side walls of the canonical instance.
    pub fn open_faces(self) -> &'static [Face] {
        match self {
            Shape::Closed => &[],
            Shape::DeadEnd => &[Face::PosZ],
            Shape::Corridor => &[Face::NegZ, Face::PosZ],
            Shape::Corner => &[Face::PosX, Face::PosZ],
            Shape::TJunction => &[Face::NegX, Face::PosX, Face::PosZ],
            Shape::Crossroads => &[Face::NegX, Face::PosX, Face::NegZ, Face::PosZ],
        }
    }

    /// Whether `face` is open.
    pub fn is_open(self, face: Face) -> bool {
        self.open_faces().contains(&face)
    }

    /// The present faces in layout order.
    pub fn present_faces(self) -> Vec<Face> {
        Face::ALL.into_iter().filter(|f| !self.is_open(*f)).collect()
    }

    /// Pairs of adjacent open side walls (the "kitty-corner" light positions of the prior).
    pub fn adjacent_open_pairs(self) -> Vec<(Face, Face)> {
        let open = self.open_faces();
        let mut pairs = Vec::new();
        for (i, a) in open.iter().enumerate() {
            for b in &open[i + 1..] {
                if a.axis() != b.axis() {
                    pairs.push((*a, *b));
                }
            }
        }
        pairs
    }
}

/// A shape's samples: `res x res` texel centres on each present face, face after face, row
/// after row (t), texel after texel (s).
#[derive(Clone, Debug)]
pub struct Layout {
    /// The shape.
    pub shape: Shape,
    /// Texels per face side.
    pub res: usize,
    /// The present faces in order; sample `slot * res^2 + t * res + s` lies on `faces[slot]`.
    pub faces: Vec<Face>,
    /// Each face's slot in `faces`, or `None` where it is open.
    slots: [Option<usize>; 6],
}

impl Layout {
    /// The layout of `shape` at `res` texels per face side.
    pub fn new(shape: Shape, res: usize) -> Self {
        let faces = shape.present_faces();
        let mut slots = [None; 6];
        for (i, f) in faces.iter().enumerate() {
            slots[*f as usize] = Some(i);
        }
        Self { shape, res, faces, slots }
    }

    /// Number of samples n.
    pub fn len(&self) -> usize {
        self.faces.len() * self.res * self.res
    }

    /// Whether there are no samples (never for a dictionary shape).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sample `i`'s face, in-plane texel (s, t), position and inward normal.
    pub fn sample(&self, i: usize) -> (Face, (usize, usize), Vec3, Vec3) {
        let per_face = self.res * self.res;
        let face = self.faces[i / per_face];
        let (s, t) = (i % per_face % self.res, i % per_face / self.res);
        let r = self.res as f32;
        let p = face.point((s as f32 + 0.5) / r, (t as f32 + 0.5) / r);
        (face, (s, t), p, face.inward_normal())
    }

    /// The first sample of `face`, or `None` where it is open.
    pub fn face_start(&self, face: Face) -> Option<usize> {
        self.slots[face as usize].map(|slot| slot * self.res * self.res)
    }

    /// The samples a bilinear lookup at in-plane (s, t) in [0, 1]^2 of `face` reads, with their
    /// weights (texel centres; clamped at the face's border). `None` where the face is open.
    pub fn bilinear(&self, face: Face, s: f32, t: f32) -> Option<[(usize, f32); 4]> {
        let start = self.face_start(face)?;
        let r = self.res as f32;
        let coord = |v: f32| {
            let x = (v * r - 0.5).clamp(0.0, r - 1.0);
            let i = (x.floor() as usize).min(self.res - 1);
            let j = (i + 1).min(self.res - 1);
            (i, j, x - i as f32)
        };
        let (s0, s1, fs) = coord(s);
        let (t0, t1, ft) = coord(t);
        let at = |s: usize, t: usize| start + t * self.res + s;
        Some([
            (at(s0, t0), (1.0 - fs) * (1.0 - ft)),
            (at(s1, t0), fs * (1.0 - ft)),
            (at(s0, t1), (1.0 - fs) * ft),
            (at(s1, t1), fs * ft),
        ])
    }
}

/// Where a ray from inside the unit cube leaves it: the face it crosses, the in-plane (s, t) of
/// the exit point, and the distance.
pub fn exit(origin: Vec3, dir: Vec3) -> (Face, f32, f32, f32) {
    let mut best = (Face::PosY, f32::INFINITY);
    for axis in 0..3 {
        let d = dir[axis];
        if d.abs() < 1e-12 {
            continue;
        }
        let (bound, positive) = if d > 0.0 { (1.0, true) } else { (0.0, false) };
        let t = ((bound - origin[axis]) / d).max(0.0);
        if t < best.1 {
            best = (Face::from_axis(axis, positive), t);
        }
    }
    let (face, t) = best;
    let p = origin + dir * t;
    let (a, b) = face.plane_axes();
    (face, p[a].clamp(0.0, 1.0), p[b].clamp(0.0, 1.0), t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_dictionary_has_twenty_four_present_and_twelve_open_faces() {
        let present: usize = Shape::ALL.iter().map(|s| s.present_faces().len()).sum();
        let open: usize = Shape::ALL.iter().map(|s| s.open_faces().len()).sum();
        assert_eq!((present, open), (24, 12), "Loos 2015 section 3.5.1");
        assert_eq!(Shape::Corner.adjacent_open_pairs(), vec![(Face::PosX, Face::PosZ)]);
        assert_eq!(Shape::Corridor.adjacent_open_pairs(), vec![]);
        assert_eq!(Shape::Crossroads.adjacent_open_pairs().len(), 4);
        assert!(Shape::ALL.iter().all(|s| !s.is_open(Face::NegY) && !s.is_open(Face::PosY)));
    }

    #[test]
    fn samples_sit_at_texel_centres_on_their_faces_with_inward_normals() {
        let layout = Layout::new(Shape::DeadEnd, 4);
        assert_eq!(layout.len(), 5 * 16);
        for i in 0..layout.len() {
            let (face, _, p, n) = layout.sample(i);
            let inside = p + n * 0.1;
            assert!(inside.cmpge(Vec3::ZERO).all() && inside.cmple(Vec3::ONE).all(), "{face:?} {p} {n}");
            assert_eq!(p[face.axis()], if face.positive() { 1.0 } else { 0.0 });
        }
        // The floor's first texel is at (1/8, 0, 1/8).
        let floor = layout.face_start(Face::NegY).expect("floor");
        assert_eq!(layout.sample(floor).2, Vec3::new(0.125, 0.0, 0.125));
        assert_eq!(layout.face_start(Face::PosZ), None, "open");
    }

    #[test]
    fn a_bilinear_lookup_at_a_texel_centre_reads_that_texel_and_weights_sum_to_one() {
        let layout = Layout::new(Shape::Closed, 4);
        let start = layout.face_start(Face::PosX).expect("present");
        let taps = layout.bilinear(Face::PosX, 0.375, 0.625).expect("present");
        let hit: Vec<_> = taps.iter().filter(|(_, w)| *w > 1e-6).collect();
        assert_eq!(hit.len(), 1);
        assert_eq!(hit[0].0, start + 2 * 4 + 1);
        let taps = layout.bilinear(Face::PosX, 0.5, 0.01).expect("present");
        assert!((taps.iter().map(|t| t.1).sum::<f32>() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn a_ray_leaves_through_the_face_it_points_at() {
        let (face, s, t, d) = exit(Vec3::new(0.5, 0.0, 0.5), Vec3::Y);
        assert_eq!((face, s, t, d), (Face::PosY, 0.5, 0.5, 1.0));
        let (face, _, _, d) = exit(Vec3::new(0.5, 0.5, 0.5), Vec3::new(1.0, 0.0, 1.0).normalize());
        assert!(matches!(face, Face::PosX | Face::PosZ) && (d - 0.5f32.hypot(0.5)).abs() < 1e-5);
        assert_eq!(Face::PosX.rotated_about_up().rotated_about_up(), Face::NegX);
    }
}
