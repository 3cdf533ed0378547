//! The docking layout (egui_tiles): which panes exist, the default arrangement, and the
//! behaviour that draws each pane. The tree is saved in eframe's storage, apart from projects.

use serde::{Deserialize, Serialize};

/// A dockable panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Pane {
    Viewport,
    Outliner,
    Properties,
    Gi,
    Inspector,
    Timings,
    Log,
}

impl Pane {
    /// Tab title.
    pub fn title(self) -> &'static str {
        match self {
            Self::Viewport => "Viewport",
            Self::Outliner => "Outliner",
            Self::Properties => "Properties",
            Self::Gi => "GI",
            Self::Inspector => "Buffer inspector",
            Self::Timings => "Timings",
            Self::Log => "Log",
        }
    }
}

/// Outliner and properties on the left, the viewport in the middle, GI and inspector on the
/// right, timings and log below.
pub fn default_tree() -> egui_tiles::Tree<Pane> {
    let mut tiles = egui_tiles::Tiles::default();
    let outliner = tiles.insert_pane(Pane::Outliner);
    let properties = tiles.insert_pane(Pane::Properties);
    let left = tiles.insert_vertical_tile(vec![outliner, properties]);
    let viewport = tiles.insert_pane(Pane::Viewport);
    let timings = tiles.insert_pane(Pane::Timings);
    let log = tiles.insert_pane(Pane::Log);
    let bottom = tiles.insert_tab_tile(vec![timings, log]);
    let centre = tiles.insert_vertical_tile(vec![viewport, bottom]);
    if let Some(egui_tiles::Tile::Container(egui_tiles::Container::Linear(l))) = tiles.get_mut(centre) {
        l.shares.set_share(viewport, 4.0);
    }
    let gi = tiles.insert_pane(Pane::Gi);
    let inspector = tiles.insert_pane(Pane::Inspector);
    let right = tiles.insert_tab_tile(vec![gi, inspector]);
    let root = tiles.insert_horizontal_tile(vec![left, centre, right]);
    if let Some(egui_tiles::Tile::Container(egui_tiles::Container::Linear(l))) = tiles.get_mut(root) {
        l.shares.set_share(centre, 3.0);
    }
    egui_tiles::Tree::new(egui::Id::unique("bouncelab layout"), root, tiles)
}
