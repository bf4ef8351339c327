//! One FMU instance: what an `fmi2Component` points to.

use std::ffi::{c_char, CString};

use super::fmu_state::LayerState;
use super::log::{self, LogCategory, LogFilter};
use super::model::{CoSimModel, Variable};
use super::state::{Function, ModelState};
use super::types::{fmi2CallbackFunctions, Status};

/// Marks a live [`Instance`] allocation (checked on every `fmi2Component` the host hands back,
/// cleared by fmi2FreeInstance; a best-effort guard against stale or foreign pointers).
pub(crate) const LIVE: u64 = 0x4859_4245_414d_4649;

/// One FMU instance. Instances share nothing: each owns its model, callbacks and name.
pub struct Instance<M> {
    pub(crate) live: u64,
    name: CString,
    /// The host's callbacks, copied by value at fmi2Instantiate.
    callbacks: fmi2CallbackFunctions,
    /// Enabled log categories.
    pub log_filter: LogFilter,
    /// State machine, times and termination flags: the FMI layer's part of an FMU state.
    pub layer: LayerState,
    /// Status of the last fmi2DoStep (fmi2GetStatus(fmi2DoStepStatus)).
    pub last_do_step_status: Status,
    /// GUID of the instance (from the scene and crate version).
    pub guid: String,
    /// (value reference, index in `model.variables()`), sorted by value reference.
    vr_index: Vec<(u32, usize)>,
    /// The model.
    pub model: M,
}

impl<M: CoSimModel> Instance<M> {
    /// A new instance in state `instantiated`. Fails if the model's value references are not
    /// unique.
    pub fn new(
        name: CString,
        callbacks: fmi2CallbackFunctions,
        logging_on: bool,
        guid: String,
        model: M,
    ) -> Result<Self, String> {
        let mut vr_index: Vec<(u32, usize)> = model
            .variables()
            .iter()
            .enumerate()
            .map(|(i, v)| (v.vr, i))
            .collect();
        vr_index.sort_unstable();
        if let Some(w) = vr_index.windows(2).find(|w| w[0].0 == w[1].0) {
            let vars = model.variables();
            return Err(format!(
                "model error: value reference {} is used by both {} and {}",
                w[0].0, vars[w[0].1].name, vars[w[1].1].name
            ));
        }
        Ok(Self {
            live: LIVE,
            name,
            callbacks,
            log_filter: LogFilter::new(logging_on),
            layer: LayerState::instantiated(),
            last_do_step_status: Status::Ok,
            guid,
            vr_index,
            model,
        })
    }

    /// The instance name given at fmi2Instantiate.
    pub fn name(&self) -> &str {
        self.name.to_str().unwrap_or("")
    }

    /// The variable with value reference `vr`, if any.
    #[inline]
    pub fn variable(&self, vr: u32) -> Option<&Variable> {
        let i = self.vr_index.binary_search_by_key(&vr, |p| p.0).ok()?;
        self.model.variables().get(self.vr_index[i].1)
    }

    /// True if messages of `category` reach the host.
    #[inline]
    pub fn logs(&self, category: LogCategory) -> bool {
        self.log_filter.enabled(category)
    }

    /// Sends `message` with `status` in its status category, if that category is on.
    pub fn log(&self, status: Status, message: &str) {
        self.log_in(status, LogCategory::for_status(status), message);
    }

    /// Sends `message` with `status` in `category`, if that category is on.
    pub fn log_in(&self, status: Status, category: LogCategory, message: &str) {
        if self.logs(category) {
            // SAFETY: the callbacks were copied from the host at fmi2Instantiate.
            unsafe { log::send(&self.callbacks, self.name_ptr(), status, category, message) };
        }
    }

    /// Debug trace (category `logAll`, status fmi2OK); `message` is only built if it is sent.
    #[inline]
    pub fn trace(&self, message: impl FnOnce() -> String) {
        if self.logs(LogCategory::All) {
            self.log(Status::Ok, &message());
        }
    }

    /// Logs `"{function}: {message}"` as an error and returns [`Status::Error`]. The state is
    /// unchanged: argument and call-sequence errors leave the instance usable.
    pub fn error(&self, function: Function, message: impl AsRef<str>) -> Status {
        self.log(
            Status::Error,
            &format!("{}: {}", function.name(), message.as_ref()),
        );
        Status::Error
    }

    /// Logs `"{function}: {message}"` as a discard and returns [`Status::Discard`] (the state is
    /// unchanged).
    pub fn discard(&self, function: Function, message: impl AsRef<str>) -> Status {
        self.log(
            Status::Discard,
            &format!("{}: {}", function.name(), message.as_ref()),
        );
        Status::Discard
    }

    /// Like [`Instance::error`] for a failure of the model: the instance goes to state `error`.
    pub fn model_error(&mut self, function: Function, message: impl AsRef<str>) -> Status {
        self.layer.state = ModelState::ERROR;
        self.error(function, message)
    }

    /// The FMI layer's part of an FMU state.
    pub fn layer_state(&self) -> LayerState {
        self.layer
    }

    /// Restores the FMI layer's part of an FMU state.
    pub fn set_layer_state(&mut self, l: &LayerState) {
        self.layer = *l;
    }

    /// Back to the values right after fmi2Instantiate (the model is reset separately).
    pub fn reset_layer(&mut self) {
        self.layer = LayerState::instantiated();
        self.last_do_step_status = Status::Ok;
    }

    fn name_ptr(&self) -> *const c_char {
        self.name.as_ptr()
    }

    /// Sends a message through `callbacks` for an instance that could not be created.
    ///
    /// # Safety
    /// `callbacks.logger`, if set, must be a valid FMI 2.0 logger.
    pub unsafe fn log_without_instance(
        callbacks: &fmi2CallbackFunctions,
        name: *const c_char,
        status: Status,
        message: &str,
    ) {
        // SAFETY: forwarded contract.
        unsafe {
            log::send(
                callbacks,
                name,
                status,
                LogCategory::for_status(status),
                message,
            )
        };
    }
}
