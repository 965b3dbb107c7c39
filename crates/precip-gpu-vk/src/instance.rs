//! The Vulkan instance: the loader, the Khronos validation layer when asked for, and a
//! debug messenger that collects every warning and error message (tests fail on any).

use std::ffi::{CStr, c_void};
use std::sync::{Arc, Mutex};

use ash::vk;
use precip_model::BackendError;

use crate::error::{map_vk, missing, no_driver};

/// The validation layer's name.
pub const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Messages the validation layer reported (warnings and errors).
pub type Messages = Arc<Mutex<Vec<String>>>;

/// An instance and its debug messenger.
pub struct Instance {
    /// The loader.
    pub entry: ash::Entry,
    /// The instance.
    pub raw: ash::Instance,
    debug: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    /// Keeps the callback's target alive as long as the messenger.
    _messages_box: Option<Box<Messages>>,
    /// What the validation layer said.
    pub messages: Messages,
    /// Whether dropping this destroys the instance (false for the caller's).
    owned: bool,
    /// Whether VK_KHR_surface is enabled (windows can be presented to).
    pub surface: bool,
}

impl std::fmt::Debug for Instance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Instance")
            .field("validation", &self.debug.is_some())
            .finish_non_exhaustive()
    }
}

unsafe extern "system" fn on_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    if severity.intersects(
        vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
            | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
    ) && !data.is_null()
        && !user.is_null()
    {
        // SAFETY: Vulkan passes a valid callback data pointer for the call's duration;
        // `user` is the `Box<Messages>` this module keeps alive with the messenger.
        let (data, messages) = unsafe { (&*data, &*(user as *const Messages)) };
        let text = if data.p_message.is_null() {
            String::from("(no message)")
        } else {
            // SAFETY: a non-null p_message is a NUL-terminated string valid for the call.
            unsafe { CStr::from_ptr(data.p_message) }
                .to_string_lossy()
                .into_owned()
        };
        if let Ok(mut m) = messages.lock() {
            m.push(format!("{severity:?}: {text}"));
        }
    }
    vk::FALSE
}

impl Instance {
    /// Loads Vulkan and creates an instance; with `validation`, the Khronos validation
    /// layer and a messenger (an error naming the package when the layer is missing).
    pub fn new(validation: bool) -> Result<Self, BackendError> {
        Self::with_extensions(validation, &[])
    }

    /// [`Instance::new`] with more instance extensions (a window system's surface
    /// extensions, from `ash_window::enumerate_required_extensions`).
    pub fn with_extensions(
        validation: bool,
        more: &[*const std::ffi::c_char],
    ) -> Result<Self, BackendError> {
        // SAFETY: loading the system's Vulkan loader; nothing else runs in between.
        let entry = unsafe { ash::Entry::load() }.map_err(|e| no_driver(&e))?;
        let app = vk::ApplicationInfo::default()
            .application_name(c"precip")
            .engine_name(c"precip")
            .api_version(vk::API_VERSION_1_1);
        let layers = [VALIDATION_LAYER.as_ptr()];
        let mut extensions = more.to_vec();
        // SAFETY: every pointer in `more` is a NUL-terminated extension name.
        let surface = more
            .iter()
            .any(|&e| unsafe { CStr::from_ptr(e) } == ash::khr::surface::NAME);
        if validation {
            extensions.push(ash::ext::debug_utils::NAME.as_ptr());
        }
        if validation {
            // SAFETY: plain enumeration on a loaded entry.
            let available = unsafe { entry.enumerate_instance_layer_properties() }
                .map_err(|e| map_vk("listing layers", e))?;
            let found = available
                .iter()
                .any(|l| l.layer_name_as_c_str().is_ok_and(|n| n == VALIDATION_LAYER));
            if !found {
                return Err(missing(
                    "VK_LAYER_KHRONOS_validation".into(),
                    "install the Khronos validation layer: `apt-get install vulkan-validationlayers`",
                ));
            }
        }
        let mut available: Vec<String> = Vec::new();
        let sources: &[Option<&CStr>] = if validation {
            &[None, Some(VALIDATION_LAYER)]
        } else {
            &[None]
        };
        for &layer in sources {
            // SAFETY: plain enumeration on a loaded entry.
            let listed = unsafe { entry.enumerate_instance_extension_properties(layer) }
                .map_err(|e| map_vk("listing instance extensions", e))?;
            available.extend(listed.iter().filter_map(|e| {
                e.extension_name_as_c_str()
                    .ok()
                    .map(|n| n.to_string_lossy().into_owned())
            }));
        }
        let absent: Vec<String> = extensions
            .iter()
            // SAFETY: every pointer is a NUL-terminated extension name (ash's
            // constants or ash-window's).
            .map(|&e| unsafe { CStr::from_ptr(e) }.to_string_lossy().into_owned())
            .filter(|name| !available.contains(name))
            .collect();
        if !absent.is_empty() {
            return Err(missing(
                absent.join(", "),
                "the Vulkan driver or loader lacks these instance extensions: update it",
            ));
        }
        let mut info = vk::InstanceCreateInfo::default()
            .application_info(&app)
            .enabled_extension_names(&extensions);
        if validation {
            info = info.enabled_layer_names(&layers);
        }
        // SAFETY: the create info and everything it points to outlive the call.
        let raw = unsafe { entry.create_instance(&info, None) }
            .map_err(|e| map_vk("creating the Vulkan instance", e))?;
        let messages: Messages = Arc::new(Mutex::new(Vec::new()));
        let mut instance = Self {
            entry,
            raw,
            debug: None,
            _messages_box: None,
            messages: messages.clone(),
            owned: true,
            surface,
        };
        if validation {
            let boxed = Box::new(messages);
            let loader = ash::ext::debug_utils::Instance::new(&instance.entry, &instance.raw);
            let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                .message_severity(
                    vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                        | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
                )
                .message_type(
                    vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                        | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                        | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
                )
                .pfn_user_callback(Some(on_message))
                .user_data(std::ptr::from_ref::<Messages>(&boxed).cast_mut().cast());
            // SAFETY: the instance has VK_EXT_debug_utils enabled; `boxed` lives in
            // `self` until the messenger is destroyed in Drop.
            let messenger = unsafe { loader.create_debug_utils_messenger(&info, None) }
                .map_err(|e| map_vk("creating the debug messenger", e))?;
            instance.debug = Some((loader, messenger));
            instance._messages_box = Some(boxed);
        }
        Ok(instance)
    }

    /// Wraps an instance the caller owns (no messenger; never destroyed here).
    #[must_use]
    pub fn external(entry: ash::Entry, raw: ash::Instance) -> Self {
        Self {
            entry,
            raw,
            debug: None,
            _messages_box: None,
            messages: Messages::default(),
            owned: false,
            surface: false,
        }
    }

    /// Whether VK_EXT_debug_utils is enabled (object names can be set).
    #[must_use]
    pub fn has_debug_utils(&self) -> bool {
        self.debug.is_some()
    }

    /// The messages so far, taken.
    #[must_use]
    pub fn take_messages(&self) -> Vec<String> {
        self.messages
            .lock()
            .map(|mut m| std::mem::take(&mut *m))
            .unwrap_or_default()
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        if let Some((loader, messenger)) = self.debug.take() {
            // SAFETY: the messenger was created from this instance and is destroyed once.
            unsafe { loader.destroy_debug_utils_messenger(messenger, None) };
        }
        if self.owned {
            // SAFETY: every child object (the device) is destroyed before the instance:
            // the backend drops its `Device` first.
            unsafe { self.raw.destroy_instance(None) };
        }
    }
}
