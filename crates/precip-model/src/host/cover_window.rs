//! [`CoverWindow`]: the cover grid follows the camera over a terrain.
//!
//! The cover grid is at most 1024² texels (512 m at 0.5 m): over kilometres of
//! terrain it is a window of fine cover round the camera, the far cover
//! ([`FarCover`]) the coarse cover of the rest. When the camera is more than a
//! quarter of the grid's side from its centre (along x or z), the grid moves by
//! whole cover tiles ([`MOVE_STEP_TEXELS`]) to centre on it, within the terrain:
//!
//! - the texels that stay keep their cover, bit for bit, on their ground;
//! - the texels that leave go into the far cover, merged into their cell's
//!   texel of their surface by area ([`FarCover::take_in`]);
//! - the texels that enter take the cover of the land they come from, per unit
//!   area, from their cell's texel ([`FarCover::lend`]);
//! - the ground map (heights, surfaces, eligibility of the scene's meshes and the
//!   terrain) is made for the strips that enter the moved grid, the rest copied;
//!   the world emitter moves with it, and the weather's site (the far cells' air
//!   offsets) is its centre.
//!
//! So snow that fell on a valley the camera left is there, per cell and surface,
//! when it comes back, and the books — the grid's and the far cover's together —
//! close over the whole terrain to rounding at every move (a merge and a lend are
//! linear in every column, [`precip_cover::CoverTexel::merged`]). The frames are
//! kept as offsets in whole texels from the configured ones, so flying away and
//! back puts the grid where it was, bit for bit.
//!
//! Every backend moves its grid here, at the start of the step after the camera
//! moved: the CPU reference on its own texels, a GPU backend on the texels it
//! reads back (the move is rare: at 70 m/s over a 512 m grid, one every ~2 s).
//! The setup asks for it (`CoverSetup::follows_camera`); without a terrain, or
//! with a sea (its depth map is the configured grid's), the grid stays where it
//! was configured.

use glam::{IVec2, Mat4, Vec2, Vec3};
use precip_cover::{CoverGrid, CoverTexel, GridFrame};

use crate::backend::error::BackendError;

use crate::backend::setup::Setup;
use crate::host::far_cover::FarCover;
use crate::particles::ground::GroundMap;

/// The grid moves by multiples of this many cover texels along x and z: whole
/// tiles of the GPU's cover lists (`precip_gpu::recipe::COVER_TILE_SIDE`).
pub const MOVE_STEP_TEXELS: i32 = 8;

/// The camera's distance from the grid's centre, as a share of the grid's side
/// (along x or z), past which the grid moves.
pub const MOVE_AT_SIDE_SHARE: f32 = 0.25;

/// The world emitter as configured over the configured ground map.
#[derive(Debug, Clone, Copy, PartialEq)]
struct HomeEmitter {
    model: Mat4,
    /// Its height over the ground map's highest point, m.
    clearance_m: f32,
    /// Its height over the ground map's lowest point, m.
    fall_m: f32,
    life_time_s: f32,
}

/// The highest and lowest heights of `ground`, m.
fn height_range_m(ground: &GroundMap) -> (f32, f32) {
    ground
        .height_m
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &h| {
            (lo.min(h), hi.max(h))
        })
}

/// Where the cover grid is, as offsets from where it was configured.
#[derive(Debug, Clone, PartialEq)]
pub struct CoverWindow {
    ground: GridFrame,
    cover: GridFrame,
    emitter: Option<HomeEmitter>,
    /// The terrain's corner and size (x, z), m; `None`: the grid never moves.
    terrain_m: Option<(Vec2, Vec2)>,
    shift: IVec2,
    moves: u32,
}

impl CoverWindow {
    /// The window of `setup`'s grids, where they were configured.
    #[must_use]
    pub fn of(setup: &Setup) -> Self {
        let terrain_m = setup
            .scene
            .as_ref()
            .filter(|_| setup.cover.follows_camera)
            .and_then(|s| {
                let sea = s.meshes.iter().any(crate::scene::Mesh::is_sea);
                let t = s.terrain()?;
                (!sea).then(|| (t.corner_m(), t.size_m()))
            });
        Self {
            ground: setup.ground.frame,
            cover: setup.cover.frame,
            emitter: setup.world_emitter.map(|e| {
                let (lo, hi) = height_range_m(&setup.ground);
                let top = e.emitter.model.w_axis.y;
                HomeEmitter {
                    model: e.emitter.model,
                    clearance_m: top - hi,
                    fall_m: top - lo,
                    life_time_s: e.emitter.life_time_s,
                }
            }),
            terrain_m,
            shift: IVec2::ZERO,
            moves: 0,
        }
    }

    /// The cover grid's offset from where it was configured, cover texels.
    #[must_use]
    pub fn shift(&self) -> IVec2 {
        self.shift
    }

    /// How many times the grid moved since configure.
    #[must_use]
    pub fn moves(&self) -> u32 {
        self.moves
    }

    /// The cover grid at `shift` texels from where it was configured.
    #[must_use]
    pub fn cover_at(&self, shift: IVec2) -> GridFrame {
        self.cover.moved_by_texels(shift)
    }

    /// The grid's offset (whole tiles) that centres it on a camera at `camera_xz_m`,
    /// within the terrain, when the camera is past [`MOVE_AT_SIDE_SHARE`] of its
    /// side from its centre now; `None` when it stays.
    #[must_use]
    pub fn shift_for(&self, camera_xz_m: Vec2) -> Option<IVec2> {
        let (corner, size) = self.terrain_m?;
        let now = self.cover_at(self.shift);
        let half = 0.5 * now.size_m;
        let centre = now.origin_m + half;
        let away = (camera_xz_m - centre).abs();
        if !(camera_xz_m.is_finite()
            && (away.x > MOVE_AT_SIDE_SHARE * now.size_m.x
                || away.y > MOVE_AT_SIDE_SHARE * now.size_m.y))
        {
            return None;
        }
        // Centred on the camera, but not past the terrain's edges where it is
        // wider than the grid.
        let lo = corner + half;
        let hi = corner + size - half;
        let target = Vec2::new(
            if lo.x <= hi.x {
                camera_xz_m.x.clamp(lo.x, hi.x)
            } else {
                centre.x
            },
            if lo.y <= hi.y {
                camera_xz_m.y.clamp(lo.y, hi.y)
            } else {
                centre.y
            },
        );
        let home_centre = self.cover.origin_m + half;
        let step = MOVE_STEP_TEXELS as f32 * self.cover.cell_m();
        // Whole tiles, rounded, then within the terrain where it is wider.
        let mut tiles = ((target - home_centre) / step).round();
        for axis in 0..2 {
            if lo[axis] <= hi[axis] {
                let least = ((lo[axis] - home_centre[axis]) / step[axis]).ceil();
                let most = ((hi[axis] - home_centre[axis]) / step[axis]).floor();
                if least <= most {
                    tiles[axis] = tiles[axis].clamp(least, most);
                }
            }
        }
        // (Far beyond any terrain a float's tiles saturate, never overflow.)
        let tiles = tiles
            .clamp(Vec2::splat(-1.0e8), Vec2::splat(1.0e8))
            .as_ivec2();
        let shift = tiles * MOVE_STEP_TEXELS;
        (shift != self.shift).then_some(shift)
    }

    /// `setup` with its grids at `shift` cover texels from where they were
    /// configured: the ground map under the moved ground frame (`None` without a
    /// scene) — what it shares with `setup`'s copied, the strips that enter made
    /// from the scene and its terrain ([`GroundMap::moved_to`]) — the world
    /// emitter moved with them.
    #[must_use]
    pub fn setup_at(&self, setup: &Setup, shift: IVec2) -> Option<Setup> {
        let scene = setup.scene.as_ref()?;
        let cover = self.cover_at(shift);
        let offset = cover.origin_m - self.cover.origin_m;
        let ground = GridFrame {
            origin_m: self.ground.origin_m + offset,
            ..self.ground
        };
        let mut moved = setup.clone();
        moved.ground = setup
            .ground
            .moved_to(ground, |f| GroundMap::of_prepared(scene, f));
        moved.cover.frame = cover;
        // The emitter over the moved ground as it was over the configured one: as
        // far over its highest point, its particles living long enough to fall
        // to its lowest.
        if let (Some(e), Some(home)) = (moved.world_emitter.as_mut(), self.emitter) {
            let (lo, hi) = height_range_m(&moved.ground);
            let top = hi + home.clearance_m;
            let rise = top - home.model.w_axis.y;
            e.emitter.model =
                Mat4::from_translation(Vec3::new(offset.x, rise, offset.y)) * home.model;
            e.emitter.life_time_s =
                home.life_time_s * ((top - lo) / home.fall_m.max(1.0e-3)).max(1.0);
        }
        Some(moved)
    }

    /// Records the grid at `shift`.
    pub fn moved_to(&mut self, shift: IVec2) {
        self.shift = shift;
        self.moves += 1;
    }
}

/// The cover of `old` moved onto `moved`'s cover grid (the same grid moved by
/// whole texels), trading with `far`: each texel of `old` off the moved grid goes
/// into the far cover first ([`FarCover::take_in`]); each texel over one of `old`
/// is that texel (its cover, masks and ground), fed as `moved` feeds it there;
/// the strips that enter are made bare from `moved`'s ground map
/// ([`Setup::bare_cover_over`], their masks ranked over each strip) and borrow
/// the far cover's ([`FarCover::lend`]). The work is the strips', not the grid's.
pub fn moved_cover(
    old: &CoverGrid,
    moved: &Setup,
    far: &mut FarCover,
) -> Result<CoverGrid, BackendError> {
    let (from, to) = (old.frame, moved.cover.frame);
    if from.texels != to.texels || old.texels.len() != from.texel_count() {
        return Err(BackendError::Setup {
            field: "cover",
            problem: "the cover to move is not the configured grid's size (a bug in precip: please report it)".into(),
        });
    }
    let area = f64::from(from.texel_area_m2());
    // Where texel (0, 0) of the moved grid lies in the old one, texels.
    let shift = ((to.origin_m - from.origin_m) / from.cell_m())
        .round()
        .as_ivec2();
    let (nx, nz) = (from.texels.x as i32, from.texels.y as i32);
    let inside = |x: i32, z: i32| x >= 0 && z >= 0 && x < nx && z < nz;
    for (k, texel) in old.texels.iter().enumerate() {
        let (x, z) = ((k as i32) % nx - shift.x, (k as i32) / nx - shift.y);
        if !inside(x, z) {
            far.take_in(from.texel_centre(k), texel, area);
        }
    }
    let mut texels = vec![CoverTexel::default(); to.texel_count()];
    for (k, texel) in texels.iter_mut().enumerate() {
        let (x, z) = ((k as i32) % nx + shift.x, (k as i32) / nx + shift.y);
        if inside(x, z) {
            let stayed = &old.texels[(x + nx * z) as usize];
            *texel = CoverTexel {
                feed: moved.feed_at(to.texel_centre(k)) as u32,
                ..stayed.with_cover_of(stayed)
            };
        }
    }
    for (first, size) in to.entering_strips(shift) {
        let strip = to.sub_grid(first, size);
        let bare = moved.bare_cover_over(strip)?;
        for (o, texel) in bare.texels.into_iter().enumerate() {
            let (x, z) = (first.x + o as u32 % size.x, first.y + o as u32 / size.x);
            let k = (x + to.texels.x * z) as usize;
            texels[k] = far.lend(to.texel_centre(k), texel, area);
        }
    }
    Ok(CoverGrid { frame: to, texels })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::UVec2;

    use super::*;
    use crate::scene::builtin::house_on_plane;
    use crate::scene::terrain::Terrain;

    /// The house on a flat 1 km square of terrain, a 64 m grid of 2 m cover
    /// texels round it, following the camera or not.
    fn setup(follows: bool) -> Setup {
        let n = 101;
        let terrain = Terrain::new(
            UVec2::splat(n),
            10.0,
            Vec2::ZERO,
            vec![-0.5; (n * n) as usize],
        )
        .expect("a terrain");
        let (mut setup, _) = Setup::over_scene(house_on_plane(), 64, 6.0, 100).expect("valid");
        let scene = setup.scene.take().expect("a scene");
        let scene = Arc::unwrap_or_clone(scene).on_terrain(Arc::new(terrain));
        setup.ground = GroundMap::of_prepared(
            &scene,
            GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(64)),
        );
        setup.scene = Some(Arc::new(scene));
        setup.cover.frame = GridFrame::centred(Vec2::ZERO, Vec2::splat(64.0), UVec2::splat(32));
        setup.cover.follows_camera = follows;
        setup
    }

    /// `ground` is the map made whole from `setup`'s scene over its frame: the
    /// same surfaces and eligibility, heights to rounding (its texel centres
    /// reckoned from other corners).
    fn assert_made_whole(ground: &GroundMap, setup: &Setup) {
        let whole = GroundMap::of_prepared(setup.scene.as_ref().expect("a scene"), ground.frame);
        assert_eq!(ground.surface, whole.surface);
        for (k, (a, b)) in ground.height_m.iter().zip(&whole.height_m).enumerate() {
            assert!((a - b).abs() < 1e-4, "texel {k}: {a} against {b}");
        }
        for (a, b) in ground.eligibility.iter().zip(&whole.eligibility) {
            assert!((a - b).abs() < 1e-5);
        }
    }

    /// A ground map moved by whole texels along either axis, either way, or both,
    /// or by more than its side, is the one made whole over the moved frame.
    #[test]
    fn a_moved_ground_map_is_the_one_made_over_its_frame() {
        let mut setup = setup(true);
        let window = CoverWindow::of(&setup);
        for shift in [
            IVec2::new(8, 0),
            IVec2::new(-8, 0),
            IVec2::new(0, 16),
            IVec2::new(-24, 8),
            IVec2::new(40, -40),
        ] {
            let moved = window.setup_at(&setup, shift).expect("a scene");
            assert_made_whole(&moved.ground, &moved);
            setup = window.setup_at(&moved, IVec2::ZERO).expect("a scene");
            assert_made_whole(&setup.ground, &setup);
        }
    }

    #[test]
    fn the_grid_moves_by_whole_tiles_once_the_camera_is_past_a_quarter_of_its_side() {
        let window = CoverWindow::of(&setup(true));
        // A quarter of 64 m is 16 m: within it the grid stays.
        assert_eq!(window.shift_for(Vec2::new(15.9, -15.9)), None);
        // Past it, the grid centres on the camera to the nearest tile (8 texels,
        // 16 m): 17 m is a tile, 40 m is 2.5 tiles, rounded to 3 (24 texels).
        assert_eq!(
            window.shift_for(Vec2::new(17.0, 0.0)),
            Some(IVec2::new(8, 0))
        );
        assert_eq!(
            window.shift_for(Vec2::new(-40.0, 3.0)),
            Some(IVec2::new(-24, 0))
        );
        // Not past the terrain's edge (500 m from the centre): the grid's side
        // stops 32 m inside it.
        let far = window.shift_for(Vec2::new(5_000.0, 0.0)).expect("moves");
        let edge = window.cover_at(far);
        assert!(edge.origin_m.x + edge.size_m.x <= 500.0 + 1e-3, "{edge:?}");
        assert!(edge.origin_m.x + edge.size_m.x > 500.0 - 16.0, "{edge:?}");
        // Not moved by a camera that is nowhere.
        assert_eq!(window.shift_for(Vec2::new(f32::NAN, 0.0)), None);
        // Moved, the next decision is from where it is.
        let mut moved = window.clone();
        moved.moved_to(IVec2::new(8, 0));
        assert_eq!(moved.shift_for(Vec2::new(17.0, 0.0)), None);
        assert_eq!(moved.moves(), 1);
        assert_eq!(
            moved.cover_at(moved.shift()).origin_m,
            Vec2::new(-16.0, -32.0)
        );
    }

    #[test]
    fn a_grid_not_asked_to_follow_or_without_a_terrain_stays() {
        assert_eq!(
            CoverWindow::of(&setup(false)).shift_for(Vec2::new(300.0, 0.0)),
            None
        );
        let mut flat = Setup::over_flat_ground(64.0, 32, 10.0, 100);
        flat.cover.follows_camera = true;
        assert_eq!(
            CoverWindow::of(&flat).shift_for(Vec2::new(300.0, 0.0)),
            None
        );
    }

    #[test]
    fn the_moved_setup_carries_its_ground_map_and_emitter_with_the_grid() {
        let setup = setup(true);
        let window = CoverWindow::of(&setup);
        let moved = window
            .setup_at(&setup, IVec2::new(16, -8))
            .expect("a scene");
        let offset = Vec2::new(32.0, -16.0);
        assert_eq!(
            moved.cover.frame.origin_m,
            setup.cover.frame.origin_m + offset
        );
        assert_eq!(
            moved.ground.frame.origin_m,
            setup.ground.frame.origin_m + offset
        );
        assert_made_whole(&moved.ground, &setup);
        let centre = |s: &Setup| {
            s.world_emitter
                .expect("an emitter")
                .emitter
                .model
                .transform_point3(Vec3::ZERO)
        };
        assert!((centre(&moved) - centre(&setup) - Vec3::new(32.0, 0.0, -16.0)).length() < 1e-4);
        // Back home, the frames are the configured ones bit for bit.
        let home = window.setup_at(&moved, IVec2::ZERO).expect("a scene");
        assert_eq!(home.cover.frame, setup.cover.frame);
        assert_eq!(home.ground.frame, setup.ground.frame);
    }
}
