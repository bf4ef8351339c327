//! One FMU instance: what an `fmi2Component` points to. Its methods in `calls.rs` are the 34
//! functions as safe Rust; this file holds the struct, its construction and its logging.

use std::ffi::{CStr, CString};

use super::fmu_state::LayerState;
use super::log::{self, LogCategory, LogFilter, Logger};
use super::model::{CoSimModel, StringVariable, Variable};
use super::state::{Function, ModelState};
use super::types::Status;

/// One FMU instance. Instances share nothing: each owns its model, logger and name.
#[derive(Debug)]
pub struct Instance<M> {
    name: CString,
    /// Where messages go.
    logger: Logger,
    /// Enabled log categories.
    pub log_filter: LogFilter,
    /// State machine, times and termination flags: the FMI layer's part of an FMU state.
    pub layer: LayerState,
    /// Status of the last fmi2DoStep (fmi2GetStatus(fmi2DoStepStatus)).
    pub last_do_step_status: Status,
    /// GUID of the instance (of its resource and the model's build).
    pub guid: String,
    /// (value reference, index in `model.variables()`), sorted by value reference.
    vr_index: Vec<(u32, usize)>,
    /// (value reference, index in `model.string_variables()`), sorted by value reference.
    string_index: Vec<(u32, usize)>,
    /// The values the last fmi2GetString returned: its pointers stay valid until the next
    /// fmi2GetString on this instance (or its fmi2FreeInstance).
    pub(crate) string_out: Vec<CString>,
    /// The model.
    pub model: M,
}

impl<M: CoSimModel> Instance<M> {
    /// A new instance in state `instantiated`. Fails if the model's value references are not
    /// unique.
    pub fn new(
        name: &str,
        logger: Logger,
        logging_on: bool,
        guid: String,
        model: M,
    ) -> Result<Self, String> {
        // (value reference, index), sorted by value reference
        let sorted = |vrs: &mut dyn Iterator<Item = u32>| {
            let mut index: Vec<(u32, usize)> = vrs.zip(0..).collect();
            index.sort_unstable();
            index
        };
        let vr_index = sorted(&mut model.variables().iter().map(|v| v.vr));
        let string_index = sorted(&mut model.string_variables().iter().map(|v| v.vr));
        // value references unique over both types (so a wrong type is named as such)
        let mut all: Vec<(u32, &str)> = vr_index
            .iter()
            .map(|&(vr, i)| (vr, model.variables()[i].name.as_str()))
            .chain(
                string_index
                    .iter()
                    .map(|&(vr, i)| (vr, model.string_variables()[i].name.as_str())),
            )
            .collect();
        all.sort_unstable();
        if let Some(w) = all.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(format!(
                "model error: value reference {} is used by both {} and {}",
                w[0].0, w[0].1, w[1].1
            ));
        }
        let mut model = model;
        model.set_instance_name(name);
        Ok(Self {
            name: log::c_string(name),
            logger,
            log_filter: LogFilter::new(logging_on),
            layer: LayerState::instantiated(),
            last_do_step_status: Status::Ok,
            guid,
            vr_index,
            string_index,
            string_out: Vec::new(),
            model,
        })
    }

    /// The instance name given at fmi2Instantiate.
    pub fn name(&self) -> &str {
        self.name.to_str().unwrap_or("")
    }

    /// The instance name as a C string.
    pub fn c_name(&self) -> &CStr {
        &self.name
    }

    /// The messages an in-memory [`Logger`] kept (empty for the host's logger).
    pub fn messages(&self) -> Vec<log::Message> {
        self.logger.messages()
    }

    /// The index in `model.variables()` of the variable with value reference `vr`, if any: the
    /// one place a value reference is resolved.
    #[inline]
    pub fn index_of(&self, vr: u32) -> Option<usize> {
        let i = self.vr_index.binary_search_by_key(&vr, |p| p.0).ok()?;
        Some(self.vr_index[i].1)
    }

    /// The index in `model.string_variables()` of the String variable with value reference
    /// `vr`, if any.
    #[inline]
    pub fn string_index_of(&self, vr: u32) -> Option<usize> {
        let i = self.string_index.binary_search_by_key(&vr, |p| p.0).ok()?;
        Some(self.string_index[i].1)
    }

    /// The String variable with value reference `vr`, if any.
    pub fn string_variable(&self, vr: u32) -> Option<&StringVariable> {
        self.model.string_variables().get(self.string_index_of(vr)?)
    }

    /// The values returned by the last fmi2GetString (what its pointers point to).
    pub fn last_strings(&self) -> &[CString] {
        &self.string_out
    }

    /// If the model has a warning to report ([`CoSimModel::take_warning`]): logs it as
    /// `"{function}: {warning}"` (fmi2Warning) and returns [`Status::Warning`], else `status`.
    pub fn with_model_warning(&mut self, function: Function, status: Status) -> Status {
        match self.model.take_warning() {
            Some(w) => {
                self.log(Status::Warning, &format!("{}: {w}", function.name()));
                status.max(Status::Warning)
            }
            None => status,
        }
    }

    /// The variable with value reference `vr`, if any.
    #[inline]
    pub fn variable(&self, vr: u32) -> Option<&Variable> {
        self.model.variables().get(self.index_of(vr)?)
    }

    /// True if messages of `category` reach the logger.
    #[inline]
    pub fn logs(&self, category: LogCategory) -> bool {
        self.log_filter.enabled(category)
    }

    /// Sends `message` with `status` in its status category, if that category is on.
    pub fn log(&self, status: Status, message: &str) {
        let category = LogCategory::for_status(status);
        if self.logs(category) {
            self.logger.send(&self.name, status, category, message);
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

    /// `Ok` if `function` may be called in the current state, else the logged fmi2Error
    /// (the one-line state check at the top of every function, as Reference-FMUs'
    /// `ASSERT_STATE`).
    pub fn check_state(&self, function: Function) -> Result<(), Status> {
        if self.layer.state.is_in(function.allowed()) {
            Ok(())
        } else {
            Err(self.error(
                function,
                format!(
                    "illegal call sequence: allowed in {}, but the instance is in {}",
                    function.allowed(),
                    self.layer.state
                ),
            ))
        }
    }

    /// Back to the values right after fmi2Instantiate (the model is reset separately).
    pub fn reset_layer(&mut self) {
        self.layer = LayerState::instantiated();
        self.last_do_step_status = Status::Ok;
    }
}
