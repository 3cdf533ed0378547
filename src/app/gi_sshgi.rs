//! The GI panel's `sshgi` section: every SshgiSettings field with its cost/quality trade-off as
//! a tooltip.

use crate::settings::SshgiSettings;

/// Draws the sshgi settings.
pub fn sshgi_ui(m: &mut SshgiSettings, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("Screen-space hierarchical GI (Soler 2010)").default_open(true).show(ui, |ui| {
        ui.horizontal(|ui| {
            ui.label("start resolution");
            for (level, name) in [(0, "full"), (1, "half"), (2, "quarter")] {
                ui.radio_value(&mut m.start_level, level, name);
            }
        })
        .response
        .on_hover_text("The start level's gather dominates the cost: each step finer costs about 4x (the paper: 6.6 ms at a quarter, 25.9 ms at half, 1280x720).");
        let mut capped = m.max_start_texels > 0;
        ui.horizontal(|ui| {
            let toggle = ui.checkbox(&mut capped, "start level at most");
            // Shown only while on: the drag value's range would clamp the 0 that means off.
            if m.max_start_texels > 0 {
                ui.add(egui::DragValue::new(&mut m.max_start_texels).range(1024..=8_294_400).speed(256.0).suffix(" texels"))
                    .labelled_by(toggle.id);
            }
        })
        .response
        .on_hover_text("Views larger than 1280x720 start a level coarser for each halving it takes to hold at most this many texels (default 320x180, the paper's quarter at 720p): 1080p starts at an eighth, 4K at a sixteenth, and most of the cost stops growing with the view (the voxelisation and the temporal filter stay per pixel). Off: the start resolution above at every view size.");
        if capped != (m.max_start_texels > 0) {
            m.max_start_texels = if capped { SshgiSettings::PAPER_START_TEXELS } else { 0 };
        }
        ui.add(egui::Slider::new(&mut m.levels, 1..=6).text("levels"))
            .on_hover_text("Each level doubles the reach for about a quarter of the previous level's cost.");
        ui.add(egui::Slider::new(&mut m.samples, 1..=1024).logarithmic(true).text("samples per level"))
            .on_hover_text("Cost: every gather is linear in it; quality: less noise (the paper: 64 or 256).");
        ui.add(egui::Slider::new(&mut m.radius, 0.0..=128.0).text("ring radius (texels, 0 = automatic)"))
            .on_hover_text("Automatic: the smallest radius whose disc on the coarsest level spans the view.");
        ui.add(egui::Slider::new(&mut m.bounces, 1..=4).text("bounces"))
            .on_hover_text("Each bounce gathers albedo x the previous one again: one more gather chain (linear cost).");
        ui.checkbox(&mut m.bounce_tail, "bounce tail")
            .on_hover_text("Not in the paper. The bounces after the last as a geometric series of it, at the ratio of the last bounce's light on screen to the previous one's (at most 0.75). `bouncelab probe`, 32 frames: clutter 0.80 to 0.88, hall 0.87 to 0.93 of the path tracer's energy, the three rooms from the unlit one 0.51 to 0.85 (quality matrix 0.71); the diorama goes over, 1.07 to 1.11, where its later bounces leak (visibility on every bounce off). Cost: three small passes over the start level.");
        ui.checkbox(&mut m.visibility, "indirect shadows (voxel visibility)")
            .on_hover_text("March a solid voxelisation of the view between receiver and sender. Off: light passes through walls; on: the paper's frame cost rose 6x.");
        ui.add_enabled(m.visibility, egui::Checkbox::new(&mut m.visibility_all_bounces, "on every bounce"))
            .on_hover_text("On by default. The paper marches the first bounce only (later bounces are smooth); off, later bounces leak: levels joined by corridors read 1.08-1.30 of the path tracer's energy off, 0.95-1.14 on. Cost: each later bounce costs as much as the first (sshgi 1.8-2.3x on a software adapter at 640x360).");
        ui.add_enabled(m.visibility, egui::Slider::new(&mut m.visibility_detail, 0..=2).text("visibility detail"))
            .on_hover_text("Voxel columns this many levels finer than the start level: coarse columns falsely shadow light leaving a surface at a grazing angle (Cornell box first bounce 0.98 / 1.00 / 1.01 of exact); each step finer doubles the march cost.");
        ui.horizontal(|ui| {
            let label = ui.label("voxel depth range (m, 0 0 = scene bounds)");
            ui.add(egui::DragValue::new(&mut m.voxel_range[0]).range(0.0..=1.0e4).speed(0.1)).labelled_by(label.id);
            ui.add(egui::DragValue::new(&mut m.voxel_range[1]).range(0.0..=1.0e4).speed(0.1)).labelled_by(label.id);
        })
        .response
        .on_hover_text("The 128 slices cover this view depth; occluders thinner than a slice can vanish.");
        let mut panorama = m.panorama > 0;
        ui.checkbox(&mut panorama, "panorama: light from surfaces off screen")
            .on_hover_text("Not in the paper. A cube G-buffer around the camera: the surfaces beside and behind the view send light too, in every bounce (the suite's window room: 0.60 to 0.88 of the path tracer's energy, hall 0.73 to 0.82, clutter 0.60 to 0.72). It cannot see what is hidden from the camera's position, and its light has no indirect shadows. Cost: six small G-buffer and lighting passes and two gathers per bounce (lavapipe: sshgi's frame x1.7).");
        if panorama != (m.panorama > 0) {
            m.panorama = if panorama { 32 } else { 0 };
        }
        ui.add_enabled(m.panorama > 0, egui::Slider::new(&mut m.panorama, 8..=128).text("panorama face (texels)"))
            .on_hover_text("Side of each of the six faces. 16 / 32 / 64 read 0.855 / 0.870 / 0.874 on the window room: the cube turns every frame, so even coarse faces average out; cost grows with the square.");
        ui.add_enabled(
            m.panorama > 0,
            egui::Slider::new(&mut m.panorama_samples, 1..=1024).logarithmic(true).text("panorama samples"),
        )
        .on_hover_text("Panorama senders per start-level texel and frame (and screen and panorama senders per panorama texel): linear cost, less noise.");
        ui.add_enabled(
            m.panorama > 0,
            egui::Slider::new(&mut m.sender_power_share, 0.0..=0.9).text("senders picked by power"),
        )
        .on_hover_text("Not in the paper. The share of those picks drawn in proportion to each sender's power instead of uniformly: where a few senders carry the light (a room lit through its doorways) the frames flicker less. 0 to 0.5: the three rooms seen from the unlit one spread 6.4% to 1.3% from frame to frame, a held-out maisonette 21% to 3.6% (its mean 0.19 to 0.47 of the path tracer's: uniform picks almost never met its lit senders). Cost: a prefix sum over the list per bounce and a binary search per pick.");
        let mut hidden = m.hidden_senders > 0;
        ui.add_enabled(m.panorama > 0, egui::Checkbox::new(&mut hidden, "hidden senders: light from surfaces the camera cannot see"))
            .on_hover_text("Not in the paper; needs the panorama. Points spread over every surface by area; those the camera's position does not see (the back of a pillar, the floor behind a box) send light too, lit by the view's lights and shadow maps, their light marched through the view's voxels and, where it leaves the view, through the world grid (quality matrix, before the world grid and the tail: Cornell box 0.91 to 0.94, clutter 0.72 to 0.77, hall 0.82 to 0.85, the three rooms seen from the unlit one 0 to 0.48 of the path tracer's energy). Cost: a pack of the points and a share of the panorama's samples.");
        if hidden != (m.hidden_senders > 0) {
            m.hidden_senders = if hidden { 2048 } else { 0 };
        }
        ui.add_enabled(
            m.panorama > 0 && m.hidden_senders > 0,
            egui::Slider::new(&mut m.hidden_senders, 64..=16384).logarithmic(true).text("hidden sender points"),
        )
        .on_hover_text("Points packed per frame (eight sets of them, one a frame). 2048 and 8192 read within 0.01 on the suite: the temporal filter averages the sets.");
        let mut world = m.world_voxels > 0;
        ui.add_enabled(
            m.panorama > 0 && m.hidden_senders > 0,
            egui::Checkbox::new(&mut world, "world grid: hidden light that leaves the view"),
        )
        .on_hover_text("Not in the paper. A grid of the voxels the scene's surfaces pass through, built on the CPU when the geometry changes: where a hidden sender's light leaves the view it is walked there instead of being counted as blocked; the senders' sky rays walk it too, and the screen's where they leave the view (`bouncelab probe`, 32 frames: hall 0.85 to 0.87, clutter 0.77 to 0.80; a 60 m hall's side room with the hall behind the camera 0.29 to 0.55 of the path tracer's energy). Cost: each such segment walks the grid's bricks (lavapipe: sshgi's passes x1.3 on the clutter room).");
        if world != (m.world_voxels > 0) {
            m.world_voxels = if world { 512 } else { 0 };
        }
        ui.add_enabled(
            m.panorama > 0 && m.hidden_senders > 0 && m.world_voxels > 0,
            egui::Slider::new(&mut m.world_voxels, 32..=512).logarithmic(true).text("world grid voxels"),
        )
        .on_hover_text("Voxels along the scene's longest side (at least 2 cm each). Finer: less false shadow near surfaces and in narrow doorways, a longer walk and up to 8x the memory per doubling.");
        ui.add_enabled(
            m.visibility && m.panorama > 0 && m.hidden_senders > 0 && m.world_voxels > 0,
            egui::Checkbox::new(&mut m.world_grid_in_view, "world grid where finer than the view's columns"),
        )
        .on_hover_text("Not in the paper. A hidden sender's light that stays in view walks the world grid instead of the view's voxel columns where the grid's voxel is smaller than a column at the segment's depth: a corridor seen down its length spans few wide columns that block light the walls let through (32 frames: a 3 m corridor level 0.85 to 0.90, the suite's three rooms 0.85 to 0.90 of the path tracer's energy). Cost: those segments walk the grid.");
        ui.add_enabled(m.visibility, egui::Slider::new(&mut m.sky_rays, 0..=64).text("sky rays"))
            .on_hover_text("Rays per start-level texel and frame that look for the sky through the voxels (0: the sky lights nothing; needs visibility). Open where a ray leaves the voxels' far end or crosses a column where the camera sees the sky; where it leaves the screen elsewhere it walks on through the world grid (blocked without it; the courtyard 0.98 to 0.99 of the path tracer's energy). Linear cost.");
        ui.add(egui::Slider::new(&mut m.temporal_weight, 0.0..=0.99).text("temporal weight a"))
            .on_hover_text("History share of the blend (0: none). Higher: less noise, more lag; history is dropped at disocclusions.");
        ui.checkbox(&mut m.temporal_two_tap, "2-tap blend (paper)")
            .on_hover_text("Blend with the previous raw frame instead of the recursive history: less lag, more noise.");
    });
}
