//! The 34 FMI 2.0 co-simulation functions as safe methods of [`Instance`], named after the C
//! functions (`do_step` ↔ `fmi2DoStep`). [`guard`](crate::guard) turns the C arguments into
//! slices, strings and references, catches panics and calls these; Rust code (a host, a unit
//! test with an in-memory [`Logger`]) can call them directly.
//!
//! Every method first checks the state against the one table ([`Instance::check_state`]), then
//! sizes and values, naming the argument and value in the logged message. Argument and
//! call-sequence errors return fmi2Error and leave the state unchanged, as in Reference-FMUs; a
//! failure of the model itself (initialize, reset) moves the instance to state `error`.

use std::ffi::CString;

use smallvec::SmallVec;

use crate::fmu_state::FmuState;
use crate::guid;
use crate::instance::Instance;
use crate::log::{LogCategory, Logger};
use crate::model::{Causality, CoSimModel, StepError, Variability, Variable};
use crate::resources;
use crate::state::{Function as F, ModelState};
use crate::types::*;

/// Relative tolerance of the communication-point and stop-time checks of fmi2DoStep.
///
/// `currentCommunicationPoint` is accepted if
/// `|t − time| ≤ min(TIME_RTOL · max(|t|, |time|, h), h/2)`.
/// Hosts compute `t0 + n·h` or a running sum, which differ from the FMU's `t + h` by a few ulps
/// of `|t|` per step; 1e-9 covers ~10⁶ accumulated roundings, and the h/2 cap keeps consecutive
/// communication points apart even at large times. After a successful step the FMU's time is
/// set to the host's `t + h`, so no drift builds up.
pub const TIME_RTOL: f64 = 1e-9;

/// Returns early with the error status of a `Result<_, Status>`.
macro_rules! tri {
    ($e:expr) => {
        match $e {
            Ok(v) => v,
            Err(status) => return status,
        }
    };
}

/// Why `var` cannot be set in `state`, if it cannot.
fn check_settable(var: &Variable, state: ModelState) -> Result<(), String> {
    match var.causality {
        Causality::Output => Err(format!(
            "{} (value reference {}) is an output and cannot be set",
            var.name, var.vr
        )),
        Causality::Input => Ok(()),
        Causality::Parameter => parameter_settable((&var.name, var.vr), var.variability, state),
    }
}

/// Why the parameter (name, value reference) of `variability` cannot be set in `state`, if it
/// cannot: a fixed one only before fmi2ExitInitializationMode, a tunable one any time. For
/// Real and String parameters alike.
fn parameter_settable(
    (name, vr): (&str, u32),
    variability: Variability,
    state: ModelState,
) -> Result<(), String> {
    if variability == Variability::Tunable
        || state.is_in(ModelState::INSTANTIATED.or(ModelState::INIT_MODE))
    {
        Ok(())
    } else {
        Err(format!(
            "{name} (value reference {vr}) is a fixed parameter: it can only be set before \
             fmi2ExitInitializationMode (the instance is in {state})"
        ))
    }
}

/// The name of a status kind, or `None` if `s` is no fmi2StatusKind.
fn status_kind_name(s: fmi2StatusKind) -> Option<&'static str> {
    match s {
        FMI2_DO_STEP_STATUS => Some("fmi2DoStepStatus"),
        FMI2_PENDING_STATUS => Some("fmi2PendingStatus"),
        FMI2_LAST_SUCCESSFUL_TIME => Some("fmi2LastSuccessfulTime"),
        FMI2_TERMINATED => Some("fmi2Terminated"),
        _ => None,
    }
}

impl<M: CoSimModel> Instance<M> {
    /// fmi2Instantiate: checks the type, reads `resources/` [`CoSimModel::RESOURCE`], checks the
    /// GUID, builds the model. The error is the message to log.
    pub fn instantiate(
        name: &str,
        fmu_type: fmi2Type,
        fmu_guid: &str,
        resource_location: Option<&str>,
        logger: Logger,
        logging_on: bool,
    ) -> Result<Self, String> {
        if fmu_type != FMI2_CO_SIMULATION {
            let kind = if fmu_type == FMI2_MODEL_EXCHANGE {
                "fmi2ModelExchange"
            } else {
                "unknown"
            };
            return Err(format!(
                "fmuType = {fmu_type} ({kind}) is not supported: this FMU implements \
                 fmi2CoSimulation only"
            ));
        }
        let location = resource_location.ok_or_else(|| {
            format!(
                "fmuResourceLocation is NULL: this FMU needs its resources/ folder ({})",
                M::RESOURCE
            )
        })?;
        let resource = resources::read_resource(location, M::RESOURCE)?;
        let expected = guid::guid::<M>(&resource);
        if !guid::same_guid(fmu_guid, &expected) {
            return Err(format!(
                "fmuGUID = {fmu_guid} does not match this FMU's GUID {expected} (from \
                 resources/{} and build {}): modelDescription.xml, binary and resources come \
                 from different builds",
                M::RESOURCE,
                M::BUILD_ID
            ));
        }
        let text = String::from_utf8(resource)
            .map_err(|_| format!("resources/{} is not valid UTF-8", M::RESOURCE))?;
        let model = M::from_resource(&text)
            .map_err(|e| format!("invalid resources/{}: {e}", M::RESOURCE))?;
        let inst = Self::new(name, logger, logging_on, expected, model)?;
        inst.trace(|| format!("fmi2Instantiate: instance \"{name}\" of GUID {}", inst.guid));
        Ok(inst)
    }

    /// fmi2FreeInstance (legal in every state).
    pub fn free_instance(self) {
        self.trace(|| "fmi2FreeInstance".to_owned());
    }

    /// fmi2SetDebugLogging: every category (empty list) or the listed ones; an unknown name
    /// changes nothing.
    pub fn set_debug_logging(&mut self, logging_on: bool, categories: &[&str]) -> Status {
        let f = F::SetDebugLogging;
        tri!(self.check_state(f));
        if categories.is_empty() {
            self.log_filter.set_all(logging_on);
            return Status::Ok;
        }
        let mut filter = self.log_filter;
        for (i, name) in categories.iter().enumerate() {
            match LogCategory::from_name(name) {
                Some(cat) => filter.set(cat, logging_on),
                None => {
                    let known: Vec<&str> = LogCategory::ALL.iter().map(|c| c.name()).collect();
                    return self.error(
                        f,
                        format!(
                            "categories[{i}] = \"{name}\" is not a log category of this FMU \
                             (known: {}); nothing was changed",
                            known.join(", ")
                        ),
                    );
                }
            }
        }
        self.log_filter = filter;
        Status::Ok
    }

    /// fmi2SetupExperiment: stores tolerance, start and stop time.
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Status {
        let f = F::SetupExperiment;
        tri!(self.check_state(f));
        if let Some(t) = tolerance.filter(|t| !(t.is_finite() && *t > 0.0)) {
            return self.error(f, format!("tolerance = {t} must be finite and > 0"));
        }
        if !start_time.is_finite() {
            return self.error(f, format!("startTime = {start_time} must be finite"));
        }
        if let Some(s) = stop_time.filter(|s| !(s.is_finite() && *s >= start_time)) {
            return self.error(
                f,
                format!("stopTime = {s} must be finite and >= startTime = {start_time}"),
            );
        }
        let l = &mut self.layer;
        l.tolerance = tolerance;
        l.start_time = start_time;
        l.stop_time = stop_time;
        l.time = start_time;
        l.last_successful_time = start_time;
        self.trace(|| {
            let opt = |x: Option<f64>| x.map_or("undefined".to_owned(), |x| x.to_string());
            format!(
                "fmi2SetupExperiment: tolerance {}, startTime {start_time}, stopTime {}",
                opt(tolerance),
                opt(stop_time)
            )
        });
        Status::Ok
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization_mode(&mut self) -> Status {
        tri!(self.check_state(F::EnterInitializationMode));
        self.layer.state = ModelState::INIT_MODE;
        self.trace(|| "fmi2EnterInitializationMode".to_owned());
        Status::Ok
    }

    /// fmi2ExitInitializationMode: `model.initialize(start_time)`, then state `stepComplete`.
    pub fn exit_initialization_mode(&mut self) -> Status {
        let f = F::ExitInitializationMode;
        tri!(self.check_state(f));
        match self.model.initialize(self.layer.start_time) {
            Ok(()) => {
                let l = &mut self.layer;
                l.state = ModelState::STEP_COMPLETE;
                l.time = l.start_time;
                l.last_successful_time = l.start_time;
                l.terminated = false;
                self.trace(|| format!("fmi2ExitInitializationMode: t = {}", self.layer.time));
                self.with_model_warning(f, Status::Ok)
            }
            Err(e) => self.model_error(f, format!("model initialization failed: {e}")),
        }
    }

    /// fmi2Terminate: `model.terminate()`, state `terminated` (the model keeps its values for
    /// fmi2GetReal); fmi2Warning if the model has a warning to report.
    pub fn terminate(&mut self) -> Status {
        let f = F::Terminate;
        tri!(self.check_state(f));
        self.model.terminate();
        self.layer.state = ModelState::TERMINATED;
        self.trace(|| format!("fmi2Terminate at t = {}", self.layer.time));
        self.with_model_warning(f, Status::Ok)
    }

    /// fmi2Reset: `model.reset()`, then state `instantiated` with the experiment cleared.
    pub fn reset(&mut self) -> Status {
        let f = F::Reset;
        tri!(self.check_state(f));
        match self.model.reset() {
            Ok(()) => {
                self.reset_layer();
                self.trace(|| "fmi2Reset".to_owned());
                self.with_model_warning(f, Status::Ok)
            }
            Err(e) => self.model_error(f, format!("model reset failed: {e}")),
        }
    }

    /// fmi2GetReal as the exported symbol runs it: the model's
    /// [`CoSimModel::before_get_real`](crate::CoSimModel::before_get_real), then
    /// [`Instance::get_real`].
    pub fn get_real_prepared(&mut self, vrs: &[fmi2ValueReference], out: &mut [f64]) -> Status {
        if self.check_state(F::GetReal).is_ok() {
            self.model.before_get_real();
        }
        self.get_real(vrs, out)
    }

    /// fmi2GetReal: `out[i]` = the value of `vrs[i]` (equal lengths).
    pub fn get_real(&self, vrs: &[fmi2ValueReference], out: &mut [f64]) -> Status {
        let f = F::GetReal;
        tri!(self.check_state(f));
        for (&r, slot) in vrs.iter().zip(out.iter_mut()) {
            let Some(index) = self.index_of(r) else {
                return self.error(f, self.not_a(r, "a Real"));
            };
            match self.model.get_real(index) {
                Ok(v) => *slot = tri!(self.finite(f, index, "", v)),
                Err(e) => return self.error(f, format!("value reference {r}: {e}")),
            }
        }
        Status::Ok
    }

    /// `v` if finite, else a logged fmi2Error naming the variable of `index` (a getter never
    /// answers a non-finite number with fmi2OK); `what` qualifies the value (a derivative).
    fn finite(&self, f: F, index: usize, what: &str, v: f64) -> Result<f64, Status> {
        if v.is_finite() {
            return Ok(v);
        }
        let var = &self.model.variables()[index];
        Err(self.error(
            f,
            format!(
                "{what}{} (value reference {}) = {v} is not finite: the model's state cannot \
                 give it (restore an earlier FMU state or reset)",
                var.name, var.vr
            ),
        ))
    }

    /// fmi2SetReal: all values are checked (variable exists, settable in this state, finite)
    /// before any is set; if the model refuses one, those already set are restored. So on
    /// fmi2Error nothing has changed.
    pub fn set_real(&mut self, vrs: &[fmi2ValueReference], values: &[f64]) -> Status {
        let f = F::SetReal;
        tri!(self.check_state(f));
        // Indices of the value references (resolved once), checked before any is set; the
        // scratch grows per element checked (on the stack up to 8), never to `nvr` up front,
        // so a host's wrong count ends at its first invalid reference.
        let mut index = SmallVec::<[usize; 8]>::new();
        for (&r, &v) in vrs.iter().zip(values) {
            let Some(found) = self.index_of(r) else {
                return self.error(f, self.not_a(r, "a Real"));
            };
            let var = &self.model.variables()[found];
            if let Err(e) = check_settable(var, self.layer.state) {
                return self.error(f, e);
            }
            if !v.is_finite() {
                return self.error(
                    f,
                    format!(
                        "{} (value reference {r}) = {v} is not finite; nothing was set",
                        var.name
                    ),
                );
            }
            index.push(found);
        }
        // Previous values, to undo if the model refuses one.
        let mut old = SmallVec::<[f64; 8]>::new();
        for (&r, &i) in vrs.iter().zip(index.iter()) {
            match self.model.get_real(i) {
                Ok(v) => old.push(v),
                Err(e) => return self.error(f, format!("value reference {r}: {e}")),
            }
        }
        for (k, ((&r, &i), &v)) in vrs.iter().zip(index.iter()).zip(values).enumerate() {
            if let Err(e) = self.model.set_real(i, v) {
                // Reverse order restores repeated value references correctly.
                for (&i_done, &v_old) in index[..k].iter().zip(&old[..k]).rev() {
                    let _ = self.model.set_real(i_done, v_old);
                }
                let name = &self.model.variables()[i].name;
                return self.error(
                    f,
                    format!("{name} (value reference {r}) = {v} refused: {e}; nothing was set"),
                );
            }
        }
        Status::Ok
    }

    /// Why `r` is not a variable of the type `wanted` ("a Real", "a String"): it is one of the
    /// other type (named), or no variable at all.
    fn not_a(&self, r: fmi2ValueReference, wanted: &str) -> String {
        if let Some(v) = self.variable(r) {
            format!(
                "value reference {r} is {}, a Real variable, not {wanted} variable",
                v.name
            )
        } else if let Some(v) = self.string_variable(r) {
            format!(
                "value reference {r} is {}, a String variable, not {wanted} variable",
                v.name
            )
        } else {
            format!("value reference {r} is not a variable of this model")
        }
    }

    /// Get/Set of a type the layer does not support (Integer, Boolean): fmi2OK for no value
    /// references, otherwise fmi2Error naming the first.
    fn no_variables_of_type(&self, f: F, vrs: &[fmi2ValueReference]) -> Status {
        tri!(self.check_state(f));
        let type_name = match f {
            F::GetInteger | F::SetInteger => "an Integer",
            _ => "a Boolean",
        };
        let types = if self.model.string_variables().is_empty() {
            "Real variables"
        } else {
            "Real and String variables"
        };
        match vrs.first() {
            None => Status::Ok,
            Some(r) => self.error(
                f,
                format!(
                    "value reference {r} is not {type_name} variable of this model (it has only \
                     {types})"
                ),
            ),
        }
    }

    /// fmi2GetInteger (no Integer variables).
    pub fn get_integer(&self, vrs: &[fmi2ValueReference], _out: &mut [fmi2Integer]) -> Status {
        self.no_variables_of_type(F::GetInteger, vrs)
    }

    /// fmi2GetBoolean (no Boolean variables).
    pub fn get_boolean(&self, vrs: &[fmi2ValueReference], _out: &mut [fmi2Boolean]) -> Status {
        self.no_variables_of_type(F::GetBoolean, vrs)
    }

    /// fmi2GetString: `out[i]` points to the value of the String variable `vrs[i]`, a copy the
    /// instance keeps until its next fmi2GetString (or fmi2FreeInstance). On fmi2Error `out` is
    /// unchanged and the previous values stay valid.
    pub fn get_string(&mut self, vrs: &[fmi2ValueReference], out: &mut [fmi2String]) -> Status {
        let f = F::GetString;
        tri!(self.check_state(f));
        // grown per element checked, never sized by a count up front
        let mut values = Vec::new();
        for &r in vrs.iter().take(out.len()) {
            let Some(index) = self.string_index_of(r) else {
                return self.error(f, self.not_a(r, "a String"));
            };
            let value = match self.model.get_string(index) {
                Ok(v) => v,
                Err(e) => return self.error(f, format!("value reference {r}: {e}")),
            };
            match CString::new(value) {
                Ok(c) => values.push(c),
                Err(_) => {
                    return self.error(
                        f,
                        format!("value reference {r}: the value holds a NUL character"),
                    )
                }
            }
        }
        self.string_out = values;
        for (slot, c) in out.iter_mut().zip(&self.string_out) {
            *slot = c.as_ptr();
        }
        Status::Ok
    }

    /// fmi2SetInteger (no Integer variables).
    pub fn set_integer(&mut self, vrs: &[fmi2ValueReference], _values: &[fmi2Integer]) -> Status {
        self.no_variables_of_type(F::SetInteger, vrs)
    }

    /// fmi2SetBoolean (no Boolean variables).
    pub fn set_boolean(&mut self, vrs: &[fmi2ValueReference], _values: &[fmi2Boolean]) -> Status {
        self.no_variables_of_type(F::SetBoolean, vrs)
    }

    /// fmi2SetString: the model copies each value (the host's memory is not kept). All value
    /// references are checked (a String variable, settable in this state) before any is set;
    /// if the model refuses one, those already set are restored: on fmi2Error nothing changed.
    pub fn set_string(&mut self, vrs: &[fmi2ValueReference], values: &[&str]) -> Status {
        let f = F::SetString;
        tri!(self.check_state(f));
        let mut index = SmallVec::<[usize; 8]>::new();
        for &r in vrs.iter().take(values.len()) {
            let Some(found) = self.string_index_of(r) else {
                return self.error(f, self.not_a(r, "a String"));
            };
            let var = &self.model.string_variables()[found];
            if let Err(e) =
                parameter_settable((&var.name, var.vr), var.variability, self.layer.state)
            {
                return self.error(f, e);
            }
            index.push(found);
        }
        let mut old = SmallVec::<[String; 8]>::new();
        for (&r, &i) in vrs.iter().zip(index.iter()) {
            match self.model.get_string(i) {
                Ok(v) => old.push(v.to_owned()),
                Err(e) => return self.error(f, format!("value reference {r}: {e}")),
            }
        }
        for (k, ((&r, &i), &v)) in vrs.iter().zip(index.iter()).zip(values).enumerate() {
            if let Err(e) = self.model.set_string(i, v) {
                for (&i_done, v_old) in index[..k].iter().zip(&old[..k]).rev() {
                    let _ = self.model.set_string(i_done, v_old);
                }
                let name = &self.model.string_variables()[i].name;
                return self.error(
                    f,
                    format!("{name} (value reference {r}) = \"{v}\" refused: {e}; nothing was set"),
                );
            }
        }
        Status::Ok
    }

    /// fmi2GetFMUstate: an owned copy (FMI layer state + `model.save_state()` + the String
    /// parameters' values).
    pub fn get_fmu_state(&self) -> Result<FmuState, Status> {
        let f = F::GetFMUstate;
        self.check_state(f)?;
        let mut strings = Vec::new();
        for (i, v) in self.model.string_variables().iter().enumerate() {
            match self.model.get_string(i) {
                Ok(x) => strings.push(x.to_owned()),
                Err(e) => return Err(self.error(f, format!("{}: {e}", v.name))),
            }
        }
        let s = FmuState::new(self.layer, self.model.save_state()).with_strings(strings);
        self.trace(|| format!("fmi2GetFMUstate at t = {}", self.layer.time));
        Ok(s)
    }

    /// fmi2SetFMUstate: the String parameters (`model.set_string` where the state's value
    /// differs), `model.load_state`, then the FMI layer state (time, state machine, flags). If
    /// the model refuses the state, the String parameters are set back: nothing changed.
    pub fn set_fmu_state(&mut self, s: &FmuState) -> Status {
        let f = F::SetFMUstate;
        tri!(self.check_state(f));
        let n = self.model.string_variables().len();
        // a state without String values (format version 1) keeps the current ones
        if !s.strings.is_empty() && s.strings.len() != n {
            return self.error(
                f,
                format!(
                    "the FMU state holds {} String values, this model has {n} String variables",
                    s.strings.len()
                ),
            );
        }
        // (index, previous value) of the String parameters changed
        let mut changed: Vec<(usize, String)> = Vec::new();
        let undo = |m: &mut M, changed: &[(usize, String)]| {
            for (i, v) in changed.iter().rev() {
                let _ = m.set_string(*i, v);
            }
        };
        for (i, v) in s.strings.iter().enumerate() {
            let old = match self.model.get_string(i) {
                Ok(x) if x == v => continue,
                Ok(x) => x.to_owned(),
                Err(e) => return self.error(f, e),
            };
            if let Err(e) = self.model.set_string(i, v) {
                undo(&mut self.model, &changed);
                let name = &self.model.string_variables()[i].name;
                return self.error(f, format!("the model refused {name} = \"{v}\": {e}"));
            }
            changed.push((i, old));
        }
        if let Err(e) = self.model.load_state(&s.model) {
            undo(&mut self.model, &changed);
            return self.error(f, format!("the model refused the FMU state: {e}"));
        }
        self.layer = s.layer;
        self.trace(|| format!("fmi2SetFMUstate: t = {}", self.layer.time));
        self.with_model_warning(f, Status::Ok)
    }

    /// fmi2FreeFMUstate: drops `*s` (a `None` is accepted); on an illegal call `*s` is kept.
    pub fn free_fmu_state(&mut self, s: &mut Option<Box<FmuState>>) -> Status {
        tri!(self.check_state(F::FreeFMUstate));
        *s = None;
        Status::Ok
    }

    /// fmi2SerializedFMUstateSize.
    pub fn serialized_fmu_state_size(&self, s: &FmuState) -> Result<usize, Status> {
        self.check_state(F::SerializedFMUstateSize)?;
        Ok(s.serialized_len(&self.guid))
    }

    /// fmi2SerializeFMUstate: `out` must have the length from fmi2SerializedFMUstateSize.
    pub fn serialize_fmu_state(&self, s: &FmuState, out: &mut [fmi2Byte]) -> Status {
        let f = F::SerializeFMUstate;
        tri!(self.check_state(f));
        let need = s.serialized_len(&self.guid);
        if out.len() != need {
            return self.error(
                f,
                format!(
                    "size = {}, but this FMU state serializes to {need} bytes (the value of \
                     fmi2SerializedFMUstateSize)",
                    out.len()
                ),
            );
        }
        for (o, b) in out.iter_mut().zip(s.serialize(&M::STATE_MAGIC, &self.guid)) {
            *o = b as fmi2Byte;
        }
        Status::Ok
    }

    /// fmi2DeSerializeFMUstate: validates the bytes (magic, format version, GUID, checksum, FMI
    /// state) and returns a new FMU state; the model bytes are checked by fmi2SetFMUstate.
    pub fn deserialize_fmu_state(&self, bytes: &[u8]) -> Result<FmuState, Status> {
        let f = F::DeSerializeFMUstate;
        self.check_state(f)?;
        FmuState::deserialize(bytes, &M::STATE_MAGIC, &self.guid).map_err(|e| {
            self.error(
                f,
                format!("serializedState ({} bytes) refused: {e}", bytes.len()),
            )
        })
    }

    /// The variable of `vr` if it has `causality` and is continuous, else the message.
    fn continuous(&self, vr: fmi2ValueReference, causality: Causality) -> Result<usize, String> {
        let Some(index) = self.index_of(vr) else {
            return Err(format!(
                "value reference {vr} is not a variable of this model"
            ));
        };
        let var = &self.model.variables()[index];
        if var.causality != causality || var.variability != Variability::Continuous {
            let what = match causality {
                Causality::Input => "a continuous input",
                _ => "a continuous output",
            };
            return Err(format!("{} (value reference {vr}) is not {what}", var.name));
        }
        Ok(index)
    }

    /// An order of a derivative call: 1..=`max` (`attribute` names the modelDescription flag).
    fn check_order(order: fmi2Integer, max: u32, attribute: &str) -> Result<u32, String> {
        match u32::try_from(order) {
            Ok(o) if (1..=max).contains(&o) => Ok(o),
            _ => Err(format!(
                "order {order} is outside 1..={max} ({attribute} = {max})"
            )),
        }
    }

    /// fmi2GetDirectionalDerivative: dv_unknown = Σ ∂unknown/∂known · dv_known for outputs
    /// (unknowns) and inputs (knowns); the partial derivatives are the model's for the inputs
    /// an output lists in `depends_on`, zero for the others. Needs
    /// `providesDirectionalDerivative="true"`. Every reference and seed is checked first.
    pub fn get_directional_derivative(
        &mut self,
        unknowns: &[fmi2ValueReference],
        knowns: &[fmi2ValueReference],
        dv_known: &[f64],
        dv_unknown: &mut [f64],
    ) -> Status {
        let f = F::GetDirectionalDerivative;
        tri!(self.check_state(f));
        if !self.model.capabilities().directional_derivative {
            return self.error(
                f,
                "not provided by this FMU (providesDirectionalDerivative=\"false\")",
            );
        }
        // grown per reference checked, never sized by a count up front
        let mut known_index = SmallVec::<[usize; 8]>::new();
        for (&r, &dv) in knowns.iter().zip(dv_known) {
            match self.continuous(r, Causality::Input) {
                Ok(i) => known_index.push(i),
                Err(e) => return self.error(f, format!("vKnown_ref: {e}")),
            }
            if !dv.is_finite() {
                return self.error(
                    f,
                    format!("dvKnown of value reference {r} = {dv} is not finite"),
                );
            }
        }
        let mut unknown_index = SmallVec::<[usize; 8]>::new();
        for &r in unknowns {
            match self.continuous(r, Causality::Output) {
                Ok(i) => unknown_index.push(i),
                Err(e) => return self.error(f, format!("vUnknown_ref: {e}")),
            }
        }
        for (out, &u) in dv_unknown.iter_mut().zip(&unknown_index) {
            let mut sum = 0.0;
            for ((&k, &kr), &dv) in known_index.iter().zip(knowns).zip(dv_known) {
                if !self.model.variables()[u].depends_on.contains(&kr) {
                    continue;
                }
                match self.model.partial_derivative(u, k) {
                    Ok(d) => sum += d * dv,
                    Err(e) => {
                        let vars = self.model.variables();
                        let msg = format!("∂{}/∂{}: {e}", vars[u].name, vars[k].name);
                        return self.error(f, msg);
                    }
                }
            }
            *out = tri!(self.finite(f, u, "the directional derivative of ", sum));
        }
        Status::Ok
    }

    /// fmi2SetRealInputDerivatives: `value[k]` is the `order[k]`-th time derivative of the
    /// continuous input `vr[k]`, for the next fmi2DoStep (the model forgets it when that step
    /// completes). Needs `canInterpolateInputs="true"`; orders 1..=the model's
    /// [`Capabilities::input_derivative_order`]. All entries are checked before any is set.
    ///
    /// [`Capabilities::input_derivative_order`]: crate::Capabilities
    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[fmi2ValueReference],
        orders: &[fmi2Integer],
        values: &[f64],
    ) -> Status {
        let f = F::SetRealInputDerivatives;
        tri!(self.check_state(f));
        let max = self.model.capabilities().input_derivative_order;
        if max == 0 {
            return self.error(
                f,
                "not supported by this FMU (canInterpolateInputs=\"false\")",
            );
        }
        let mut checked = SmallVec::<[(usize, u32, f64); 8]>::new();
        for ((&r, &o), &v) in vrs.iter().zip(orders).zip(values) {
            let index = tri!(self
                .continuous(r, Causality::Input)
                .map_err(|e| self.error(f, e)));
            let order = tri!(
                Self::check_order(o, max, "the input derivative order of this FMU")
                    .map_err(|e| self.error(f, format!("value reference {r}: {e}")))
            );
            if !v.is_finite() {
                return self.error(
                    f,
                    format!("value reference {r}: derivative of order {order} = {v} is not finite"),
                );
            }
            checked.push((index, order, v));
        }
        for (index, order, v) in checked {
            if let Err(e) = self.model.set_input_derivative(index, order, v) {
                return self.error(f, e);
            }
        }
        Status::Ok
    }

    /// fmi2GetRealOutputDerivatives: `value[k]` = the `order[k]`-th time derivative of the
    /// continuous output `vr[k]` at the current time; orders 1..=`maxOutputDerivativeOrder`.
    pub fn get_real_output_derivatives(
        &self,
        vrs: &[fmi2ValueReference],
        orders: &[fmi2Integer],
        out: &mut [f64],
    ) -> Status {
        let f = F::GetRealOutputDerivatives;
        tri!(self.check_state(f));
        let max = self.model.capabilities().output_derivative_order;
        if max == 0 {
            return self.error(
                f,
                "not supported by this FMU (maxOutputDerivativeOrder=\"0\")",
            );
        }
        for ((&r, &o), slot) in vrs.iter().zip(orders).zip(out.iter_mut()) {
            let index = tri!(self
                .continuous(r, Causality::Output)
                .map_err(|e| self.error(f, e)));
            let order = tri!(Self::check_order(o, max, "maxOutputDerivativeOrder")
                .map_err(|e| self.error(f, format!("value reference {r}: {e}"))));
            match self.model.get_output_derivative(index, order) {
                Ok(v) => *slot = tri!(self.finite(f, index, "the derivative of ", v)),
                Err(e) => return self.error(f, format!("value reference {r}: {e}")),
            }
        }
        Status::Ok
    }

    /// fmi2DoStep: checks the step (`h` finite and > 0, `t` finite, `t + h` finite and later
    /// than `t` in floating point, `t` equal to the FMU time within [`TIME_RTOL`], `t + h` not
    /// beyond stopTime), then `model.do_step(t, h)`. Ok → fmi2OK and time = `t + h`. Err →
    /// fmi2Discard, state `stepFailed`, fmi2LastSuccessfulTime = the time before the step (the
    /// model keeps its last good state), fmi2Terminated = true only for
    /// [`StepError::Terminate`]; after a recoverable [`StepError::Discard`] fmi2SetFMUstate
    /// resumes, e.g. to retry with a smaller step.
    pub fn do_step(&mut self, t: f64, h: f64) -> Status {
        let f = F::DoStep;
        tri!(self.check_state(f));
        if !(h.is_finite() && h > 0.0) {
            return self.error(
                f,
                format!("communicationStepSize = {h} must be finite and > 0"),
            );
        }
        if !t.is_finite() {
            return self.error(f, format!("currentCommunicationPoint = {t} must be finite"));
        }
        let end = t + h;
        if !(end.is_finite() && end > t) {
            let spacing = t.abs().next_up() - t.abs();
            return self.error(
                f,
                format!(
                    "communicationStepSize = {h:e} does not advance time from \
                     currentCommunicationPoint = {t:e}: t + h = {end:e} in double precision (at \
                     |t| = {:e} s consecutive times are {spacing:e} s apart); use a larger \
                     step, or a start time nearer 0",
                    t.abs()
                ),
            );
        }
        let time = self.layer.time;
        let tol = (TIME_RTOL * t.abs().max(time.abs()).max(h)).min(0.5 * h);
        if (t - time).abs() > tol {
            return self.error(
                f,
                format!(
                    "currentCommunicationPoint = {t} differs from the FMU time {time} by {:e} \
                     (tolerance {tol:e}): each step must start where the last one ended",
                    t - time
                ),
            );
        }
        if let Some(stop) = self.layer.stop_time {
            if end > stop + TIME_RTOL * stop.abs().max(h) {
                return self.error(
                    f,
                    format!(
                        "currentCommunicationPoint + communicationStepSize = {end} is beyond \
                         stopTime = {stop}"
                    ),
                );
            }
        }
        self.trace(|| format!("fmi2DoStep: t = {t}, h = {h}"));
        match self.model.do_step(t, h) {
            Ok(()) => {
                self.layer.time = end;
                self.layer.last_successful_time = end;
                let status = self.with_model_warning(f, Status::Ok);
                self.last_do_step_status = status;
                status
            }
            Err(e) => {
                let terminate = matches!(e, StepError::Terminate(_));
                self.layer.state = ModelState::STEP_FAILED;
                self.layer.terminated = terminate;
                self.layer.last_successful_time = time;
                self.last_do_step_status = Status::Discard;
                let next = if terminate {
                    "fmi2Terminated = true: the model cannot continue"
                } else {
                    "fmi2Terminated = false: fmi2SetFMUstate to a saved state continues, e.g. \
                     with a smaller step or other inputs"
                };
                self.log(
                    Status::Discard,
                    &format!(
                        "fmi2DoStep: the step from t = {t} with h = {h} failed: {}; the model \
                         keeps its state at t = {time} ({next})",
                        e.message()
                    ),
                );
                Status::Discard
            }
        }
    }

    /// fmi2CancelStep: this FMU never runs asynchronous steps, so it is never in
    /// `stepInProgress`.
    pub fn cancel_step(&mut self) -> Status {
        let f = F::CancelStep;
        tri!(self.check_state(f));
        self.error(f, "this FMU runs no asynchronous step to cancel")
    }

    /// A status query for a kind this function does not provide: fmi2Discard (FMI 2.0 §4.2.3)
    /// for a kind that exists, fmi2Error for a value that is no status kind.
    fn unavailable_status(&self, f: F, s: fmi2StatusKind, available: &str) -> Status {
        match status_kind_name(s) {
            Some(name) => self.discard(
                f,
                format!("status kind {s} ({name}) is not available ({available})"),
            ),
            None => self.error(
                f,
                format!("s = {s} is not an fmi2StatusKind (0 to 3); {available}"),
            ),
        }
    }

    /// fmi2GetStatus: `fmi2DoStepStatus` gives the status of the last fmi2DoStep.
    pub fn get_status(&self, s: fmi2StatusKind) -> Result<Status, Status> {
        let f = F::GetStatus;
        self.check_state(f)?;
        if s == FMI2_DO_STEP_STATUS {
            Ok(self.last_do_step_status)
        } else {
            Err(self.unavailable_status(f, s, "only fmi2DoStepStatus = 0"))
        }
    }

    /// fmi2GetRealStatus: `fmi2LastSuccessfulTime`.
    pub fn get_real_status(&self, s: fmi2StatusKind) -> Result<f64, Status> {
        let f = F::GetRealStatus;
        self.check_state(f)?;
        if s == FMI2_LAST_SUCCESSFUL_TIME {
            Ok(self.layer.last_successful_time)
        } else {
            Err(self.unavailable_status(f, s, "only fmi2LastSuccessfulTime = 2"))
        }
    }

    /// fmi2GetIntegerStatus: FMI 2.0 defines no Integer status.
    pub fn get_integer_status(&self, s: fmi2StatusKind) -> Status {
        let f = F::GetIntegerStatus;
        tri!(self.check_state(f));
        self.unavailable_status(f, s, "FMI 2.0 defines no Integer status")
    }

    /// fmi2GetBooleanStatus: `fmi2Terminated`.
    pub fn get_boolean_status(&self, s: fmi2StatusKind) -> Result<bool, Status> {
        let f = F::GetBooleanStatus;
        self.check_state(f)?;
        if s == FMI2_TERMINATED {
            Ok(self.layer.terminated)
        } else {
            Err(self.unavailable_status(f, s, "only fmi2Terminated = 3"))
        }
    }

    /// fmi2GetStringStatus: `fmi2PendingStatus` only exists while a step is pending, which
    /// never happens here.
    pub fn get_string_status(&self, s: fmi2StatusKind) -> Status {
        let f = F::GetStringStatus;
        tri!(self.check_state(f));
        self.unavailable_status(f, s, "this FMU never has a pending step")
    }
}

#[cfg(test)]
mod tests;
