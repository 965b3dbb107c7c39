//! What a device must let a pipeline bind, and the check made once, when a
//! backend is made on a device ([`crate::backend::GpuBackend::new`]).
//!
//! precip opens its own devices with the adapter's limits, but an engine hands
//! precip the device it opened, often with WebGPU's default limits
//! ([`BindingLimits::WEBGPU_DEFAULT`]) or fewer. A pipeline layout over those
//! limits is a validation error inside the graphics library (wgpu panics in its
//! default error handler); the check turns it into a [`BackendError`] that names
//! the limit, the pipeline and what to ask for instead.
//!
//! What the plan needs ([`BindingLimits::needed`]) is counted from the bind-group
//! tables ([`crate::bind_groups::groups_of`]) for every entry point of the
//! programs a configuration and its frames use ([`FRAME_PROGRAMS`]), per shader
//! stage, for WebGPU's per-stage and per-layout limits (Vulkan's
//! `maxPerStageDescriptor*`, `maxBoundDescriptorSets` and
//! `maxDescriptorSet*Dynamic` are the same counts: its backend binds samplers and
//! sampled images apart). Not checked: Vulkan's per-layout totals
//! (`maxDescriptorSetStorageBuffers`, at least 24 where a layout holds 9) and
//! `maxPerStageResources`, and wgpu's bindings per group — none near a device's
//! least; wgpu's layouts are made inside its error scopes, so one over them is a
//! typed error too.

use precip_model::BackendError;

use crate::bind_groups::{Binding, BindingKind, Stages, groups_of};
use crate::shaders::Program;

/// The programs of a configuration and its frames (not the test probes).
pub const FRAME_PROGRAMS: [Program; 6] = [
    Program::StepParticles,
    Program::CoverUpdate,
    Program::CullParticles,
    Program::Render,
    Program::QueryBeams,
    Program::OpticsSums,
];

/// The stages a binding may be seen by, as limits count them.
const STAGE_NAMES: [&str; 3] = ["vertex", "fragment", "compute"];

/// How many of each kind of binding a pipeline may have (per stage, except the
/// groups and the dynamic buffers, which count per pipeline layout): WebGPU's
/// names (`max_storage_buffers_per_shader_stage`, …), Vulkan's
/// `maxPerStageDescriptor*` and `maxDescriptorSet*Dynamic`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BindingLimits {
    /// Bind groups (descriptor sets) a pipeline binds.
    pub bind_groups: u32,
    /// Storage buffers a stage sees.
    pub storage_buffers_per_stage: u32,
    /// Uniform buffers a stage sees.
    pub uniform_buffers_per_stage: u32,
    /// Sampled textures a stage sees.
    pub sampled_textures_per_stage: u32,
    /// Samplers a stage sees.
    pub samplers_per_stage: u32,
    /// Storage textures a stage sees.
    pub storage_textures_per_stage: u32,
    /// Uniform buffers bound with a dynamic offset, a pipeline.
    pub dynamic_uniform_buffers: u32,
    /// Storage buffers bound with a dynamic offset, a pipeline.
    pub dynamic_storage_buffers: u32,
}

/// One limit a pipeline goes over.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shortfall {
    /// The limit, in WebGPU's name.
    pub limit: &'static str,
    /// What the device allows.
    pub allowed: u32,
    /// What the pipeline needs.
    pub needed: u32,
    /// The program and entry point (and stage, for a per-stage limit).
    pub at: String,
}

impl BindingLimits {
    /// WebGPU's default limits (W3C WebGPU, "Limits"): what a device opened
    /// without asking for more has.
    pub const WEBGPU_DEFAULT: Self = Self {
        bind_groups: 4,
        storage_buffers_per_stage: 8,
        uniform_buffers_per_stage: 12,
        sampled_textures_per_stage: 16,
        samplers_per_stage: 16,
        storage_textures_per_stage: 4,
        dynamic_uniform_buffers: 8,
        dynamic_storage_buffers: 4,
    };

    /// The limits with their WebGPU names, in order.
    fn named(self) -> [(&'static str, u32); 8] {
        [
            ("max_bind_groups", self.bind_groups),
            (
                "max_storage_buffers_per_shader_stage",
                self.storage_buffers_per_stage,
            ),
            (
                "max_uniform_buffers_per_shader_stage",
                self.uniform_buffers_per_stage,
            ),
            (
                "max_sampled_textures_per_shader_stage",
                self.sampled_textures_per_stage,
            ),
            ("max_samplers_per_shader_stage", self.samplers_per_stage),
            (
                "max_storage_textures_per_shader_stage",
                self.storage_textures_per_stage,
            ),
            (
                "max_dynamic_uniform_buffers_per_pipeline_layout",
                self.dynamic_uniform_buffers,
            ),
            (
                "max_dynamic_storage_buffers_per_pipeline_layout",
                self.dynamic_storage_buffers,
            ),
        ]
    }

    /// What the pipeline of `program`'s `entry_point` binds, its stages' counts
    /// the largest of its three; `None` for an entry point without groups.
    #[must_use]
    pub fn of_entry_point(program: Program, entry_point: &str) -> Option<Self> {
        let [vertex, fragment, compute] = Self::per_stage(program, entry_point)?;
        Some(vertex.max(fragment).max(compute))
    }

    /// What the pipeline of `program`'s `entry_point` binds as its vertex,
    /// fragment and compute stages see it (the groups and the dynamic buffers
    /// the pipeline's in each).
    fn per_stage(program: Program, entry_point: &str) -> Option<[Self; 3]> {
        let groups = groups_of(program, entry_point)?;
        let bindings = || groups.iter().flat_map(|g| g.bindings.iter());
        let all = |f: fn(&Binding) -> bool| bindings().filter(|b| f(b)).count() as u32;
        Some(std::array::from_fn(|s| {
            let seen = |f: fn(&Binding) -> bool| {
                bindings().filter(|b| seen_by(b.stages, s) && f(b)).count() as u32
            };
            Self {
                bind_groups: groups.len() as u32,
                storage_buffers_per_stage: seen(|b| matches!(b.kind, BindingKind::Storage { .. })),
                uniform_buffers_per_stage: seen(|b| matches!(b.kind, BindingKind::Uniform { .. })),
                sampled_textures_per_stage: seen(|b| matches!(b.kind, BindingKind::Texture { .. })),
                samplers_per_stage: seen(|b| matches!(b.kind, BindingKind::Sampler { .. })),
                storage_textures_per_stage: seen(|b| {
                    matches!(b.kind, BindingKind::StorageTextureRgba16Float)
                }),
                dynamic_uniform_buffers: all(|b| {
                    matches!(b.kind, BindingKind::Uniform { dynamic: true, .. })
                }),
                dynamic_storage_buffers: all(|b| {
                    matches!(b.kind, BindingKind::Storage { dynamic: true, .. })
                }),
            }
        }))
    }

    /// The most any pipeline of [`FRAME_PROGRAMS`] binds, limit by limit.
    #[must_use]
    pub fn needed() -> Self {
        let mut most = Self::zero();
        for program in FRAME_PROGRAMS {
            for entry in program.entry_points() {
                if let Some(n) = Self::of_entry_point(program, entry) {
                    most = most.max(n);
                }
            }
        }
        most
    }

    const fn zero() -> Self {
        Self::from_values([0; 8])
    }

    /// The limits of [`BindingLimits::named`]'s values, in its order.
    const fn from_values(v: [u32; 8]) -> Self {
        Self {
            bind_groups: v[0],
            storage_buffers_per_stage: v[1],
            uniform_buffers_per_stage: v[2],
            sampled_textures_per_stage: v[3],
            samplers_per_stage: v[4],
            storage_textures_per_stage: v[5],
            dynamic_uniform_buffers: v[6],
            dynamic_storage_buffers: v[7],
        }
    }

    fn max(self, other: Self) -> Self {
        let (a, b) = (self.named(), other.named());
        Self::from_values(std::array::from_fn(|k| a[k].1.max(b[k].1)))
    }

    /// Every limit of a device with these limits that a pipeline of
    /// [`FRAME_PROGRAMS`] goes over, the first pipeline to go over each.
    #[must_use]
    pub fn shortfalls(&self) -> Vec<Shortfall> {
        let allowed = self.named();
        let mut found: Vec<Shortfall> = Vec::new();
        for program in FRAME_PROGRAMS {
            for entry in program.entry_points() {
                let Some(stages) = Self::per_stage(program, entry) else {
                    continue;
                };
                for (stage, needs) in STAGE_NAMES.iter().zip(stages) {
                    for (k, ((limit, allowed), (_, needed))) in
                        allowed.iter().zip(needs.named()).enumerate()
                    {
                        if needed > *allowed && !found.iter().any(|s| s.limit == *limit) {
                            // The groups and the dynamic buffers are the pipeline's.
                            let per_stage = (1..=5).contains(&k);
                            found.push(Shortfall {
                                limit,
                                allowed: *allowed,
                                needed,
                                at: if per_stage {
                                    format!("{} `{entry}` ({stage} stage)", program.label())
                                } else {
                                    format!("{} `{entry}`", program.label())
                                },
                            });
                        }
                    }
                }
            }
        }
        found
    }

    /// Whether a device with these limits, named `device`, runs every pipeline
    /// of [`FRAME_PROGRAMS`]; if not, an error that names each limit it falls
    /// short of, a pipeline that needs more, and what to open the device with.
    pub fn admit(&self, device: &str) -> Result<(), BackendError> {
        let short = self.shortfalls();
        if short.is_empty() {
            return Ok(());
        }
        let each: Vec<String> = short
            .iter()
            .map(|s| {
                format!(
                    "{} is {} but {} needs {}",
                    s.limit, s.allowed, s.at, s.needed
                )
            })
            .collect();
        Err(BackendError::Setup {
            field: "device",
            problem: format!(
                "{device} was opened with limits too small for precip's pipelines: {}; open it with at least WebGPU's default limits (wgpu::Limits::default()), or with the adapter's",
                each.join("; ")
            ),
        })
    }
}

/// Whether a binding seen by `stages` is seen by stage `s` (0 vertex, 1
/// fragment, 2 compute).
const fn seen_by(stages: Stages, s: usize) -> bool {
    match stages {
        Stages::Compute => s == 2,
        Stages::Draw => s < 2,
        Stages::Fragment => s == 1,
        Stages::DrawAndCompute => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pipeline_layout_fits_webgpu_s_default_limits() {
        assert_eq!(BindingLimits::WEBGPU_DEFAULT.shortfalls(), Vec::new());
        assert!(BindingLimits::WEBGPU_DEFAULT.admit("a device").is_ok());
    }

    /// The default limits are tight where the plan is: one storage buffer less
    /// a stage is refused, naming the limit and a pipeline at it.
    #[test]
    fn a_device_one_storage_buffer_short_is_refused_with_the_limit_named() {
        let needed = BindingLimits::needed();
        assert_eq!(
            needed.storage_buffers_per_stage,
            BindingLimits::WEBGPU_DEFAULT.storage_buffers_per_stage
        );
        let short = BindingLimits {
            storage_buffers_per_stage: needed.storage_buffers_per_stage - 1,
            ..BindingLimits::WEBGPU_DEFAULT
        };
        let found = short.shortfalls();
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].limit, "max_storage_buffers_per_shader_stage");
        assert_eq!((found[0].allowed, found[0].needed), (7, 8));
        assert!(found[0].at.contains("stage"), "{found:?}");
        let message = short
            .admit("an engine's device")
            .expect_err("refused")
            .to_string();
        assert!(
            message.contains("an engine's device")
                && message.contains("max_storage_buffers_per_shader_stage is 7")
                && message.contains("wgpu::Limits::default()"),
            "{message}"
        );
    }

    /// Each limit is counted: a device with none of anything falls short of
    /// every limit the plan uses.
    #[test]
    fn a_device_with_no_bindings_falls_short_of_every_limit_the_plan_uses() {
        let needed = BindingLimits::needed().named();
        let found = BindingLimits::zero().shortfalls();
        let used: Vec<&str> = needed
            .iter()
            .filter(|(_, n)| *n > 0)
            .map(|(l, _)| *l)
            .collect();
        let short: Vec<&str> = found.iter().map(|s| s.limit).collect();
        assert_eq!(short.len(), used.len(), "{short:?} against {used:?}");
        for limit in used {
            assert!(short.contains(&limit), "{limit}");
        }
        // The frame draws with textures and samplers, kernels write storage
        // textures, the particles' blocks are dynamic.
        let n = BindingLimits::needed();
        assert!(n.sampled_textures_per_stage > 0 && n.samplers_per_stage > 0);
        assert!(n.dynamic_uniform_buffers > 0 && n.bind_groups >= 3);
    }

    /// An entry point's count is its busiest stage's: the particles' composite
    /// sees 8 storage buffers in its fragment stage, fewer in its vertex stage.
    #[test]
    fn the_counts_are_the_busiest_stage_s() {
        let [vertex, fragment, _] =
            BindingLimits::per_stage(Program::Render, "fs_particles_composite").expect("groups");
        assert_eq!(fragment.storage_buffers_per_stage, 8);
        assert!(vertex.storage_buffers_per_stage < 8);
        let composite = BindingLimits::of_entry_point(Program::Render, "fs_particles_composite")
            .expect("groups");
        assert_eq!(composite.storage_buffers_per_stage, 8);
        assert!(BindingLimits::of_entry_point(Program::StepParticles, "step_particles").is_some());
    }
}
