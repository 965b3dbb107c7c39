//! Every GPU program parses and validates with naga, has its entry points, and every
//! struct that crosses to the GPU has the same size and member offsets in WGSL as its
//! `#[repr(C)]` Rust twin.

use std::collections::HashMap;
use std::mem::{offset_of, size_of};

use naga::valid::{Capabilities, ValidationFlags, Validator};
use precip_gpu::bind_groups::{BindingKind, Stages, TextureSample, groups_of};
use precip_gpu::recipe::OpticsParams;
use precip_gpu::recipe::{DrawArgs, FrameDraws, Frames, ProbeDrawing};
use precip_gpu::shaders::Program;
use precip_model::Particle;
use precip_model::cover::{CoverStepParams, CoverTexel, GridFrame};
use precip_model::drawing::render::RenderParams;
use precip_model::particles::step::StepParams;
use precip_model::sensors::lidar::{Beam, BeamHit, BeamParams};
use precip_model::sensors::optics::OpticsPartial;
use precip_model::wind::WindParams;

fn parse(program: Program) -> naga::Module {
    let source = program.source();
    naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("{program:?} does not parse:\n{}", e.emit_to_string(&source)))
}

#[test]
fn every_program_validates_with_all_its_entry_points() {
    for program in Program::ALL {
        let module = parse(program);
        Validator::new(ValidationFlags::all(), Capabilities::default())
            .validate(&module)
            .unwrap_or_else(|e| {
                panic!(
                    "{program:?} is invalid:\n{}",
                    e.emit_to_string(&program.source())
                )
            });
        for name in program.entry_points() {
            assert!(
                module.entry_points.iter().any(|ep| ep.name == *name),
                "{program:?} lacks {name}"
            );
        }
        assert_eq!(
            module.entry_points.len(),
            program.entry_points().len(),
            "{program:?}"
        );
    }
}

/// WGSL struct name → (size, member name → offset).
fn wgsl_layouts() -> HashMap<String, (u32, HashMap<String, u32>)> {
    let mut out = HashMap::new();
    for program in [
        Program::StepParticles,
        Program::CoverUpdate,
        Program::Render,
        Program::CullParticles,
        Program::ProbeDrawing,
        Program::QueryBeams,
        Program::OpticsSums,
    ] {
        let module = parse(program);
        for (_, ty) in module.types.iter() {
            if let naga::TypeInner::Struct { members, span } = &ty.inner {
                let offsets = members
                    .iter()
                    .filter_map(|m| Some((m.name.clone()?, m.offset)))
                    .collect();
                out.insert(ty.name.clone().unwrap_or_default(), (*span, offsets));
            }
        }
    }
    out
}

macro_rules! rust_layout {
    ($ty:ty { $($field:ident),* $(,)? }) => {
        (stringify!($ty), size_of::<$ty>(), vec![$((stringify!($field), offset_of!($ty, $field))),*])
    };
}

#[test]
fn rust_and_wgsl_layouts_match() {
    let wgsl = wgsl_layouts();
    let rust = [
        rust_layout!(Particle {
            position_m,
            age_s,
            velocity_mps,
            terminal_speed_mps,
            rotation_rad,
            flags,
            diameter_m,
            water_kg,
            generation,
            rotation0
        }),
        rust_layout!(StepParams {
            emitter_model,
            emitter_size_m,
            emitter_life_time_s,
            emitter_velocity_spread_mps,
            emitter_velocity_mps,
            water_per_particle_kg_per_s,
            camera_centre_m,
            dt_s,
            camera_half_extent_m,
            time_s,
            mean_wind_mps,
            air_temperature_c,
            world_rotation,
            camera_rotation,
            seed,
            world_count,
            particle_count,
            snow_is_wet,
            deposit_scale_mm_per_kg,
            ground_floor_m,
            lift_from,
            lift_per_particle_kg_per_s,
            friction_velocity_mps,
            lift_layer_top_m,
            grain_suspended,
            flow_ceiling_m,
            lift_area_min_m,
            lift_area_max_m,
            wall_rebound_speed_mps,
            step_first,
            step_end,
            reserved2,
            species
        }),
        rust_layout!(Beam {
            origin_m,
            divergence_rad,
            direction,
            max_range_m
        }),
        rust_layout!(BeamHit {
            particle_range_m,
            particle_diameter_m,
            particle_flags,
            target_range_m
        }),
        rust_layout!(OpticsPartial {
            extinction_m2,
            sampled,
            backscatter_m2_sr,
            reserved
        }),
        rust_layout!(OpticsParams {
            particle_count,
            reserved0,
            reserved1,
            reserved2
        }),
        rust_layout!(BeamParams {
            beam_count,
            particle_first,
            particle_end,
            aperture_radius_m,
            march_step_m,
            reserved0,
            reserved1,
            reserved2
        }),
        rust_layout!(GridFrame {
            origin_m,
            size_m,
            texels,
            reserved
        }),
        rust_layout!(Frames {
            ground,
            cover,
            waves
        }),
        rust_layout!(WindParams {
            mean_wind_mps,
            gust_factor,
            extent_m,
            reserved0,
            texels,
            reserved1
        }),
        rust_layout!(CoverStepParams {
            melt_threshold_c,
            melt_proportionality_mm_per_c_day,
            solar_irradiance_factor,
            vegetation_density,
            albedo_decay_per_day,
            refreeze_factor_mm_per_c_day,
            water_holding_fraction,
            cover_depletion_exponent,
            settled_density_kg_m3,
            compaction_time_days,
            wet_darkening,
            wetting_mm,
            mask_edge,
            snow_rate_mm_per_day,
            rain_rate_mm_per_day,
            air_temperature_c,
            relative_humidity,
            wind_speed_mps,
            dt_days,
            flow_iteration_s,
            cell_x_m,
            cell_z_m,
            texel_count,
            texels_x,
            wind_x_mps,
            wind_z_mps,
            snow_repose_tan,
            drift_iteration_s,
            origin_x_m,
            origin_z_m,
            reserved
        }),
        rust_layout!(CoverTexel {
            swe_mm,
            liquid_mm,
            depth_mm,
            age_days,
            peak_swe_mm,
            wetness,
            runoff_mm,
            deposited_mm,
            eligibility,
            accumulation_mask,
            melt_mask,
            feed,
            film_mm,
            standing_mm,
            infiltrated_mm,
            evaporated_mm,
            net_inflow_mm,
            ground_m,
            surface,
            moving_density_kg_m3,
            outflow_mm,
            drifted_mm,
            wind_factor,
            saltation_kg_per_m_s,
            edge_drifted_mm,
            dust_kg_m2,
            reserved1
        }),
        rust_layout!(RenderParams {
            view_proj,
            sun_view_proj,
            camera_m_cone_cos,
            view_dir_pixel_angle,
            to_sun_extinction,
            sky_colour_time,
            light,
            shadow,
            sizing,
            cover_look,
            cover_look2,
            water_look,
            ground,
            cover,
            waves,
            counts,
            pools,
            camera_box_centre_m,
            camera_box_half_m,
            lens,
            inverse_view_proj,
            previous_view_proj,
            mirror_view_proj,
            mirror,
            fog_layer,
            clouds,
            cloud_drift,
            cloud_shadow,
            far_ground,
            cloud_shadow_map,
            unresolved_streaks,
            streak_direction,
            streak_origin,
            ocean_wind,
            ocean,
            sea_colour,
            sea_attenuation,
            sea_bed,
            ocean_spectrum,
            shore_grid,
            shore_size,
            shore_edges,
            shore_steps,
            shore_waves
        }),
        rust_layout!(DrawArgs {
            vertex_count,
            instance_count,
            first_vertex,
            first_instance
        }),
        rust_layout!(FrameDraws {
            snow,
            rain,
            splatted,
            sprite_particles,
            snow_made
        }),
        rust_layout!(ProbeDrawing {
            centre_m,
            side_m,
            camera_m,
            spin_rad,
            velocity_mps,
            tumble,
            h_m,
            a_m,
            cover
        }),
    ];
    for (name, size, fields) in rust {
        let (span, offsets) = wgsl
            .get(name)
            .unwrap_or_else(|| panic!("no WGSL struct {name}"));
        assert_eq!(
            *span as usize, size,
            "{name}: WGSL size {span} vs Rust {size}"
        );
        for (field, offset) in fields {
            let wgsl_offset = offsets
                .get(field)
                .unwrap_or_else(|| panic!("WGSL {name} has no member {field}"));
            assert_eq!(*wgsl_offset as usize, offset, "{name}.{field}");
        }
        assert!(offsets.len() >= 2, "{name}");
    }
    // The snow quads have no Rust twin (only the GPU reads and writes them), but the
    // buffer is sized from their bytes.
    let (span, _) = wgsl.get("SnowQuad").expect("WGSL struct SnowQuad");
    assert_eq!(
        u64::from(*span),
        precip_gpu::recipe::SNOW_QUAD_BYTES,
        "SnowQuad"
    );
}

/// Whether `kind` can hold the WGSL global `var` of `module`.
fn kind_matches(module: &naga::Module, var: &naga::GlobalVariable, kind: BindingKind) -> bool {
    use naga::{AddressSpace, ImageClass, ImageDimension, StorageAccess, TypeInner};
    match (var.space, kind) {
        (AddressSpace::Uniform, BindingKind::Uniform { .. }) => true,
        (AddressSpace::Storage { access }, BindingKind::Storage { read_only, .. }) => {
            read_only != access.contains(StorageAccess::STORE)
        }
        (AddressSpace::Handle, kind) => match (&module.types[var.ty].inner, kind) {
            (TypeInner::Sampler { comparison }, BindingKind::Sampler { comparison: c }) => {
                *comparison == c
            }
            (TypeInner::Image { dim, class, .. }, BindingKind::Texture { sample, volume }) => {
                (*dim == ImageDimension::D3) == volume
                    && matches!(
                        (class, sample),
                        (ImageClass::Sampled { .. }, TextureSample::Float { .. })
                            | (ImageClass::Depth { .. }, TextureSample::Depth)
                    )
            }
            (
                TypeInner::Image {
                    dim: ImageDimension::D2,
                    class: ImageClass::Storage { format, .. },
                    ..
                },
                BindingKind::StorageTextureRgba16Float,
            ) => *format == naga::StorageFormat::Rgba16Float,
            _ => false,
        },
        _ => false,
    }
}

fn stage_sees(stages: Stages, stage: naga::ShaderStage) -> bool {
    use naga::ShaderStage as S;
    match stages {
        Stages::Compute => stage == S::Compute,
        Stages::Draw => matches!(stage, S::Vertex | S::Fragment),
        Stages::Fragment => stage == S::Fragment,
        Stages::DrawAndCompute => matches!(stage, S::Vertex | S::Fragment | S::Compute),
    }
}

/// The binding tables both backends build their layouts from
/// (`precip_gpu::bind_groups`) against naga's reflection of the WGSL: every resource
/// an entry point uses is in its group's table, of the same kind, visible to its stage.
#[test]
fn the_binding_tables_match_the_wgsl() {
    let mut checked = 0;
    for program in [
        Program::StepParticles,
        Program::CoverUpdate,
        Program::CullParticles,
        Program::Render,
    ] {
        let module = parse(program);
        let info = Validator::new(ValidationFlags::all(), Capabilities::default())
            .validate(&module)
            .expect("valid");
        for (index, ep) in module.entry_points.iter().enumerate() {
            let groups = groups_of(program, &ep.name)
                .unwrap_or_else(|| panic!("{program:?} {} has no groups", ep.name));
            let uses = info.get_entry_point(index);
            let mut used = 0;
            for (handle, var) in module.global_variables.iter() {
                let Some(rb) = &var.binding else {
                    continue;
                };
                if uses[handle].is_empty() {
                    continue;
                }
                used += 1;
                let name = var.name.as_deref().unwrap_or("?");
                let group = groups.get(rb.group as usize).unwrap_or_else(|| {
                    panic!(
                        "{} uses {name} in group {}, which it is not given",
                        ep.name, rb.group
                    )
                });
                let entry = group
                    .bindings
                    .iter()
                    .find(|b| b.binding == rb.binding)
                    .unwrap_or_else(|| {
                        panic!(
                            "{}: {name} (binding {}) is not in {}",
                            ep.name, rb.binding, group.name
                        )
                    });
                assert!(
                    kind_matches(&module, var, entry.kind),
                    "{}: {name} does not match {:?} in {}",
                    ep.name,
                    entry.kind,
                    group.name
                );
                assert!(
                    stage_sees(entry.stages, ep.stage),
                    "{}: {name} is not visible to {:?} in {}",
                    ep.name,
                    ep.stage,
                    group.name
                );
            }
            checked += used;
        }
    }
    assert!(checked > 40, "only {checked} resources checked");
}

/// The value of WGSL constant `name` of `module` (a `u32` or `i32` literal).
fn wgsl_integer(module: &naga::Module, name: &str) -> i64 {
    let constant = module
        .constants
        .iter()
        .map(|(_, c)| c)
        .find(|c| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no WGSL constant {name}"));
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::U32(v)) => i64::from(v),
        naga::Expression::Literal(naga::Literal::I32(v)) => i64::from(v),
        ref e => panic!("{name} is {e:?}"),
    }
}

#[test]
fn the_cover_tiles_are_the_same_in_wgsl_and_rust() {
    use precip_gpu::recipe::{COVER_TILE_REACH, COVER_TILE_SIDE, CoverTileSet};
    let module = parse(Program::CoverUpdate);
    assert_eq!(
        wgsl_integer(&module, "COVER_TILE_SIDE"),
        i64::from(COVER_TILE_SIDE)
    );
    assert_eq!(
        wgsl_integer(&module, "COVER_TILE_REACH"),
        i64::from(COVER_TILE_REACH)
    );
    assert_eq!(
        wgsl_integer(&module, "WATER_TILES"),
        CoverTileSet::Water as i64
    );
    assert_eq!(
        wgsl_integer(&module, "SNOW_TILES"),
        CoverTileSet::Snow as i64
    );
}

#[test]
fn the_flow_s_thresholds_are_their_rust_twins() {
    use precip_model::cover::water::{LEVEL_WATER_M, STILL_WATER_MM};
    let module = parse(Program::CoverUpdate);
    for (name, rust) in [
        ("LEVEL_WATER_M", f64::from(LEVEL_WATER_M)),
        ("STILL_WATER_MM", f64::from(STILL_WATER_MM)),
    ] {
        let wgsl = wgsl_constant(&module, name);
        assert!(
            (wgsl - rust).abs() <= 1e-6 * rust.abs(),
            "{name}: WGSL {wgsl}, Rust {rust}"
        );
    }
}

/// A WGSL module's `const NAME` as a number (a literal).
/// The components of the WGSL `vec` constant `name` of `module`.
fn wgsl_vector(module: &naga::Module, name: &str) -> Vec<f32> {
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no const {name}"));
    let naga::Expression::Compose { ref components, .. } = module.global_expressions[constant.init]
    else {
        panic!("const {name} is not a vector");
    };
    components
        .iter()
        .map(|&e| match module.global_expressions[e] {
            naga::Expression::Literal(naga::Literal::F32(v)) => v,
            ref other => panic!("{name}: {other:?}"),
        })
        .collect()
}

fn wgsl_constant(module: &naga::Module, name: &str) -> f64 {
    let (_, constant) = module
        .constants
        .iter()
        .find(|(_, c)| c.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no const {name}"));
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::F32(v)) => f64::from(v),
        naga::Expression::Literal(naga::Literal::U32(v)) => f64::from(v),
        naga::Expression::Literal(naga::Literal::I32(v)) => f64::from(v),
        ref other => panic!("const {name} is not a literal: {other:?}"),
    }
}

#[test]
#[expect(
    clippy::float_cmp,
    reason = "a twin's constant is the same literal, bit for bit"
)]
fn the_sea_s_constants_are_their_rust_twins() {
    use precip_gpu::recipe::OCEAN_ATLAS_PX;
    use precip_model::drawing::sea as s;
    let module = parse(Program::Render);
    for (name, rust) in [
        ("BREAKER_INDEX", f64::from(s::BREAKER_INDEX)),
        ("SEA_DEPTH_RANGE_M", f64::from(s::SEA_DEPTH_RANGE_M)),
        ("OCEAN_ATLAS_SIDE", f64::from(OCEAN_ATLAS_PX[1])),
        (
            "OCEAN_FFT_STAGES",
            f64::from(precip_sea::ocean::OCEAN_N.trailing_zeros()),
        ),
    ] {
        assert_eq!(wgsl_constant(&module, name), rust, "{name}");
    }
}

#[test]
#[expect(
    clippy::float_cmp,
    reason = "a twin's constant is the same literal, bit for bit"
)]
fn the_clouds_constants_are_their_rust_twins() {
    use precip_model::drawing::clouds as c;
    use precip_model::drawing::far_ground as g;
    let module = parse(Program::Render);
    for (name, rust) in [
        ("CLOUD_MARCH_BLOCK_PX", f64::from(c::CLOUD_MARCH_BLOCK_PX)),
        ("CLOUD_MARCH_ALL", f64::from(c::CLOUD_MARCH_ALL)),
        ("CLOUD_HISTORY_MARGIN", f64::from(c::CLOUD_HISTORY_MARGIN)),
        ("CLOUD_HISTORY_SLACK", f64::from(c::CLOUD_HISTORY_SLACK)),
        ("CLOUD_FRESH_WEIGHT", f64::from(c::CLOUD_FRESH_WEIGHT)),
        (
            "CLOUD_PARALLAX_DEPTH_M",
            f64::from(c::CLOUD_PARALLAX_DEPTH_M),
        ),
        (
            "CLOUD_PARALLAX_FULL_PX",
            f64::from(c::CLOUD_PARALLAX_FULL_PX),
        ),
        ("CLOUD_SHADOW_MAP_PX", f64::from(c::CLOUD_SHADOW_MAP_PX)),
        (
            "CLOUD_SHADOW_MAP_SPAN_M",
            f64::from(c::CLOUD_SHADOW_MAP_SPAN_M),
        ),
        ("CLOUD_SHADOW_MAP_FADE", f64::from(c::CLOUD_SHADOW_MAP_FADE)),
        ("CLOUD_SHADOW_SAMPLES", f64::from(c::CLOUD_SHADOW_SAMPLES)),
        (
            "LOCAL_WEATHER_RADIUS_M",
            f64::from(c::LOCAL_WEATHER_RADIUS_M),
        ),
        ("RAIN_SHAFT_SAMPLES", f64::from(c::RAIN_SHAFT_SAMPLES)),
        ("CLOUD_BASE_SKY_SHARE", f64::from(c::CLOUD_BASE_SKY_SHARE)),
        ("MAX_CLOUD_LAYERS", c::MAX_CLOUD_LAYERS as f64),
        ("CLOUD_DETAIL_PERIOD_M", f64::from(c::CLOUD_DETAIL_PERIOD_M)),
        ("CLOUD_DETAIL_PX", f64::from(c::CLOUD_DETAIL_PX)),
        (
            "CLOUD_DETAIL_ATLAS_COLUMNS",
            f64::from(c::CLOUD_DETAIL_ATLAS_COLUMNS),
        ),
        ("CLOUD_DETAIL_TILE_PX", f64::from(c::CLOUD_DETAIL_TILE_PX)),
        ("CLOUD_DETAIL_ATLAS_PX", f64::from(c::CLOUD_DETAIL_ATLAS_PX)),
        ("CLOUD_BILLOW_SHARE", f64::from(c::CLOUD_BILLOW_SHARE)),
    ] {
        assert_eq!(wgsl_constant(&module, name), rust, "{name}");
    }
    for (name, rust) in [
        ("FAR_GROUND_BARE_COLOUR", g::FAR_GROUND_BARE_COLOUR),
        ("FAR_GROUND_SNOW_TINT", g::FAR_GROUND_SNOW_TINT),
    ] {
        assert_eq!(wgsl_vector(&module, name), rust.to_array(), "{name}");
    }
}

#[test]
fn the_terrain_s_constants_are_their_rust_twins() {
    use precip_model::scene::land_cover::LAND_CLASSES;
    use precip_model::scene::terrain as t;
    use precip_model::scene::{FULL_SNOW_SLOPE_DEG, NO_SNOW_SLOPE_DEG};
    let module = parse(Program::Render);
    for (name, rust) in [
        ("CLIPMAP_QUADS", f64::from(t::CLIPMAP_QUADS)),
        ("CLIPMAP_MORPH_QUADS", f64::from(t::CLIPMAP_MORPH_QUADS)),
        (
            "CLIPMAP_LEVEL_VERTICES",
            f64::from(t::CLIPMAP_LEVEL_VERTICES),
        ),
        ("CLIPMAP_GRID_VERTICES", f64::from(t::CLIPMAP_GRID_VERTICES)),
        (
            "CLIPMAP_WINDOW_SAMPLES",
            f64::from(t::CLIPMAP_WINDOW_SAMPLES),
        ),
        ("TERRAIN_EDGE_ON", f64::from(t::TERRAIN_EDGE_ON)),
        ("LAND_CLASSES", LAND_CLASSES as f64),
        (
            "FULL_SNOW_COS",
            f64::from(FULL_SNOW_SLOPE_DEG.to_radians().cos()),
        ),
        (
            "NO_SNOW_COS",
            f64::from(NO_SNOW_SLOPE_DEG.to_radians().cos()),
        ),
        (
            "TERRAIN_GRASS_COS",
            f64::from(t::TERRAIN_GRASS_SLOPE_DEG.to_radians().cos()),
        ),
        (
            "FAR_SLOTS",
            precip_model::host::FAR_COVER_SURFACES.len() as f64,
        ),
        ("FAR_ROW_FLOATS", precip_model::host::FAR_ROW_FLOATS as f64),
        ("FAR_MASK", f64::from(precip_model::host::FAR_MASK)),
        (
            "GRID_BLEND_SHARE",
            f64::from(precip_model::host::GRID_BLEND_SHARE),
        ),
    ] {
        let wgsl = wgsl_constant(&module, name);
        assert!(
            (wgsl - rust).abs() < 1e-6,
            "{name}: WGSL {wgsl}, Rust {rust}"
        );
    }
    // The far cover's slots' surfaces, as precip_cover::Surface's raw values.
    let rust: Vec<f32> = precip_model::host::FAR_COVER_SURFACES
        .iter()
        .map(|&s| s as u32 as f32)
        .collect();
    assert_eq!(
        wgsl_vector(&module, "FAR_SLOT_SURFACES"),
        rust,
        "FAR_SLOT_SURFACES"
    );
}
