//! The backends under test, opened the same way for every suite in `tests/`: the CPU
//! reference, wgpu on every adapter found, and precip's Vulkan backend under the
//! Khronos validation layer (its messages are checked by [`Subject::check_clean`]).
//!
//! Without a GPU the GPU subjects are left out with a printed reason, unless
//! `PRECIP_REQUIRE_GPU=1`, which makes that a failure (CI sets it).
//!
//! # Example
//!
//! A contract case as the suites write them: the same set-up on every backend, the
//! same answer (here, the same number of particles, and a clean validation log).
//!
//! ```
//! use precip_model::Setup;
//!
//! let setup = Setup::over_flat_ground(10.0, 8, 6.0, 500);
//! for mut subject in precip_conformance::all_subjects("crate example") {
//!     subject.backend.configure(&setup).expect("configures");
//!     subject.backend.step(0.1).expect("steps");
//!     let particles = subject.backend.read_particles().expect("reads back");
//!     assert_eq!(particles.len(), 500, "{}", subject.name);
//!     subject.check_clean("the example");
//! }
//! ```

use precip_gpu_vk::VkBackend;
use precip_gpu_wgpu::{WgpuBackend, adapters};
use precip_model::{Backend, CpuBackend};

/// One backend under test.
pub struct Subject {
    /// What it is: "cpu", "wgpu: llvmpipe (Vulkan)", "vk: llvmpipe".
    pub name: String,
    /// The backend.
    pub backend: Box<dyn Backend>,
    /// The Vulkan validation layer's log, for the vk backend.
    validation: Option<precip_gpu_vk::Messages>,
}

impl std::fmt::Debug for Subject {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Subject").field("name", &self.name).finish()
    }
}

impl Subject {
    /// Panics with the validation layer's messages, if any were reported.
    pub fn check_clean(&self, when: &str) {
        if let Some(log) = &self.validation {
            let messages = log.lock().map(|m| m.clone()).unwrap_or_default();
            assert!(
                messages.is_empty(),
                "{}: the validation layer reported, {when}:\n{}",
                self.name,
                messages.join("\n")
            );
        }
    }

    /// Whether it renders.
    #[must_use]
    pub fn renders(&self) -> bool {
        self.backend.info().renders
    }
}

fn require_gpu() -> bool {
    std::env::var("PRECIP_REQUIRE_GPU").as_deref() == Ok("1")
}

fn missing(test: &str, what: &str) {
    assert!(!require_gpu(), "{test}: PRECIP_REQUIRE_GPU=1 but {what}");
    eprintln!("SKIPPED {test}: {what}");
}

/// The GPU backends: wgpu on every adapter, then vk (validation on).
#[must_use]
pub fn gpu_subjects(test: &str) -> Vec<Subject> {
    let mut subjects = Vec::new();
    let found = adapters();
    if found.is_empty() {
        missing(
            test,
            "no wgpu adapter found (install mesa-vulkan-drivers for lavapipe)",
        );
    }
    for adapter in &found {
        let info = adapter.get_info();
        let name = format!("wgpu: {} ({:?})", info.name, info.backend);
        match WgpuBackend::on_adapter(adapter) {
            Ok(b) => subjects.push(Subject {
                name,
                backend: Box::new(b),
                validation: None,
            }),
            Err(e) => missing(test, &format!("{name}: {e}")),
        }
    }
    match VkBackend::new(true) {
        Ok(b) => {
            let validation = Some(b.validation_log());
            subjects.push(Subject {
                name: format!("vk: {}", b.device_name()),
                backend: Box::new(b),
                validation,
            });
        }
        Err(e) => missing(test, &format!("vk: {e}")),
    }
    subjects
}

/// Runs `on_wgpu` on wgpu over every adapter, then `on_vk` on the Vulkan backend
/// (validation on, its messages checked after), each with the backend's name: for
/// suites that read what only the GPU backends give (their frame's buffers and
/// textures), so they need the concrete types.
pub fn each_gpu_backend(
    test: &str,
    mut on_wgpu: impl FnMut(&str, &mut WgpuBackend),
    mut on_vk: impl FnMut(&str, &mut VkBackend),
) {
    let found = adapters();
    if found.is_empty() {
        missing(test, "no wgpu adapter found");
    }
    for adapter in &found {
        let name = format!("wgpu: {}", adapter.get_info().name);
        match WgpuBackend::on_adapter(adapter) {
            Ok(mut backend) => on_wgpu(&name, &mut backend),
            Err(e) => missing(test, &format!("{name}: {e}")),
        }
    }
    match VkBackend::new(true) {
        Ok(mut backend) => {
            let log = backend.validation_log();
            let name = format!("vk: {}", backend.device_name());
            on_vk(&name, &mut backend);
            let messages = log.lock().map(|m| m.clone()).unwrap_or_default();
            assert!(
                messages.is_empty(),
                "{test}, {name}: the validation layer: {}",
                messages.join("\n")
            );
        }
        Err(e) => missing(test, &format!("vk: {e}")),
    }
}

/// Every backend: the CPU reference first, then [`gpu_subjects`].
#[must_use]
pub fn all_subjects(test: &str) -> Vec<Subject> {
    let mut subjects = vec![Subject {
        name: "cpu".into(),
        backend: Box::new(CpuBackend::new()),
        validation: None,
    }];
    subjects.extend(gpu_subjects(test));
    subjects
}

/// Resident memory of this process, KiB (`None` where /proc is not available).
#[must_use]
pub fn resident_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    status
        .lines()
        .find(|l| l.starts_with("VmRSS:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()
}
