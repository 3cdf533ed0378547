//! Viewport overlays drawn with egui's painter over the rendered image: light icons, spot
//! cones, directional arrows, proxy-block wireframes with their openings, clutter and selection
//! outlines.

use glam::{Vec2, Vec3};

use super::edits::Selection;
use super::gizmo::View;
use crate::scene::{LightKind, MeshSource, ObjectRole, Scene};

const LIGHT: egui::Color32 = egui::Color32::from_rgb(255, 220, 90);
const PROXY: egui::Color32 = egui::Color32::from_rgb(90, 200, 255);
const CLUTTER: egui::Color32 = egui::Color32::from_rgb(255, 140, 40);
const SELECTED: egui::Color32 = egui::Color32::from_rgb(255, 255, 255);
const OPENING: egui::Color32 = egui::Color32::from_rgb(120, 255, 160);

fn to_pos(rect: egui::Rect, s: Vec2) -> egui::Pos2 {
    rect.min + egui::vec2(s.x, s.y)
}

fn line(painter: &egui::Painter, rect: egui::Rect, view: &View, a: Vec3, b: Vec3, stroke: egui::Stroke) {
    if let (Some(pa), Some(pb)) = (view.project(a), view.project(b)) {
        painter.line_segment([to_pos(rect, pa), to_pos(rect, pb)], stroke);
    }
}

/// Screen position of light `i`'s icon (directional lights sit above the scene centre).
pub fn light_anchor(scene: &Scene, i: usize) -> Option<Vec3> {
    let light = scene.lights().get(i)?;
    Some(match light.kind {
        LightKind::Directional => scene.bounds().map_or(Vec3::Y, |b| Vec3::new(b.center().x, b.max.y, b.center().z)),
        _ => light.position,
    })
}

/// The 8 corners of an object's mesh bounds in world space, if it has a mesh.
fn box_corners(scene: &Scene, i: usize) -> Option<[Vec3; 8]> {
    let object = scene.objects().get(i)?;
    let b = scene.resources().meshes.get(object.mesh)?.bounds()?;
    let m = object.transform.matrix();
    Some(std::array::from_fn(|k| {
        let c = Vec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        );
        m.transform_point3(c)
    }))
}

const EDGES: [(usize, usize); 12] =
    [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)];

fn wire_box(painter: &egui::Painter, rect: egui::Rect, view: &View, c: &[Vec3; 8], stroke: egui::Stroke) {
    for (a, b) in EDGES {
        line(painter, rect, view, c[a], c[b], stroke);
    }
}

/// Corner indices of each face (+X, -X, +Y, -Y, +Z, -Z) of `box_corners`.
const FACES: [[usize; 4]; 6] = [[1, 3, 7, 5], [0, 2, 6, 4], [2, 3, 7, 6], [0, 1, 5, 4], [4, 5, 7, 6], [0, 1, 3, 2]];

/// Marks open faces of a proxy block with a cross (its interfaces to neighbouring blocks).
fn open_faces(painter: &egui::Painter, rect: egui::Rect, view: &View, c: &[Vec3; 8], openings: &[bool; 6]) {
    let stroke = egui::Stroke::new(2.0, OPENING);
    for (face, open) in FACES.iter().zip(openings) {
        if *open {
            line(painter, rect, view, c[face[0]], c[face[2]], stroke);
            line(painter, rect, view, c[face[1]], c[face[3]], stroke);
        }
    }
}

/// Draws all overlays; proxy blocks only with `blocks` (in `mrt`, the technique they serve) or
/// when selected, so that they do not cross the view in the other modes.
pub fn draw(painter: &egui::Painter, rect: egui::Rect, view: &View, scene: &Scene, selection: Selection, blocks: bool) {
    for (i, object) in scene.objects().iter().enumerate() {
        let Some(c) = box_corners(scene, i) else { continue };
        let selected = selection == Selection::Object(i);
        match object.role {
            ObjectRole::ProxyBlock if !blocks && !selected => {}
            ObjectRole::ProxyBlock => {
                wire_box(painter, rect, view, &c, egui::Stroke::new(if selected { 2.5 } else { 1.5 }, PROXY));
                if let MeshSource::Cuboid { openings, .. } = &object.source {
                    open_faces(painter, rect, view, &c, openings);
                }
            }
            ObjectRole::Clutter => {
                wire_box(painter, rect, view, &c, egui::Stroke::new(if selected { 2.5 } else { 1.0 }, CLUTTER))
            }
            ObjectRole::Static if selected => wire_box(painter, rect, view, &c, egui::Stroke::new(1.5, SELECTED)),
            ObjectRole::Static => {}
        }
    }
    for (i, light) in scene.lights().iter().enumerate() {
        let Some(anchor) = light_anchor(scene, i) else { continue };
        let Some(s) = view.project(anchor) else { continue };
        let selected = selection == Selection::Light(i);
        let colour = egui::Color32::from_rgb(
            (light.color[0].clamp(0.0, 1.0) * 255.0) as u8,
            (light.color[1].clamp(0.0, 1.0) * 255.0) as u8,
            (light.color[2].clamp(0.0, 1.0) * 255.0) as u8,
        );
        painter.circle(
            to_pos(rect, s),
            if selected { 8.0 } else { 6.0 },
            colour,
            egui::Stroke::new(1.5, if selected { SELECTED } else { LIGHT }),
        );
        let stroke = egui::Stroke::new(1.0, LIGHT);
        match light.kind {
            LightKind::Spot { outer_cone_angle, inner_cone_angle } => {
                let len = view.world_size(anchor, 80.0);
                let (t, b) = crate::scene::basis::basis(light.direction);
                for (angle, n) in [(outer_cone_angle, 8), (inner_cone_angle, 0)] {
                    let r = len * angle.tan().min(10.0);
                    let rim: Vec<Vec3> = (0..24)
                        .map(|k| {
                            let a = k as f32 / 24.0 * std::f32::consts::TAU;
                            anchor + light.direction * len + (t * a.cos() + b * a.sin()) * r
                        })
                        .collect();
                    for k in 0..24 {
                        line(painter, rect, view, rim[k], rim[(k + 1) % 24], stroke);
                    }
                    for k in (0..24).step_by(24 / n.max(1)).take(n) {
                        line(painter, rect, view, anchor, rim[k], stroke);
                    }
                }
            }
            LightKind::Directional => {
                let len = view.world_size(anchor, 60.0);
                line(painter, rect, view, anchor, anchor + light.direction * len, egui::Stroke::new(2.0, LIGHT));
            }
            LightKind::Point => {
                if let Some(range) = light.range {
                    let (t, b) = (Vec3::X, Vec3::Z);
                    let rim: Vec<Vec3> = (0..32)
                        .map(|k| {
                            let a = k as f32 / 32.0 * std::f32::consts::TAU;
                            anchor + (t * a.cos() + b * a.sin()) * range
                        })
                        .collect();
                    for k in 0..32 {
                        line(painter, rect, view, rim[k], rim[(k + 1) % 32], stroke);
                    }
                }
            }
        }
    }
}

/// Draws a technique's markers (ISM's VPLs, rcs records with the rings of their zones): a dot
/// coloured by the marker's tone, and a circle of its world radius where it has one.
pub fn draw_markers(painter: &egui::Painter, rect: egui::Rect, view: &View, markers: &[crate::render::gi::Overlay]) {
    for l in markers.iter().flat_map(|o| &o.lines) {
        let [r, g, b] = super::inspector::false_colour(l.tone);
        line(painter, rect, view, l.a, l.b, egui::Stroke::new(l.width, egui::Color32::from_rgb(r, g, b)));
    }
    for p in markers.iter().flat_map(|o| &o.points) {
        let Some(s) = view.project(p.position) else { continue };
        let [r, g, b] = super::inspector::false_colour(p.tone);
        let (centre, colour) = (rect.min + egui::vec2(s.x, s.y), egui::Color32::from_rgb(r, g, b));
        painter.circle_filled(centre, p.radius, colour);
        if p.ring > 0.0 {
            let pixels = p.ring / view.world_size(p.position, 1.0).max(1e-9);
            painter.circle_stroke(centre, pixels.min(4096.0), egui::Stroke::new(1.0, colour.gamma_multiply(0.6)));
        }
    }
}
