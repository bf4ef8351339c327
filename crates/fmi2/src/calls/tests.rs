//! The 34 functions as safe methods, driven without a C host: a small model, an in-memory
//! logger, and the FMI 2.0 rules the methods enforce.

use super::*;
use crate::log::Message;
use crate::model::{ModelInfo, StringVariable};

/// `x' = k·u + g`: input `u` (VR 1), output `x` (VR 2), fixed `k` (VR 3), tunable `g` (VR 4).
/// A step with |u| > 1 is refused (recoverable); one that would take x beyond 100 ends the
/// model (`StepError::Terminate`). String parameters: fixed `label` (VR 5, refuses "bad"),
/// tunable `note` (VR 6; "warn" makes every successful step report a warning).
struct Ramp {
    vars: Vec<Variable>,
    strings: Vec<StringVariable>,
    label: String,
    note: String,
    warning: Option<String>,
    x: f64,
    u: f64,
    k: f64,
    g: f64,
}

fn var(name: &str, vr: u32, causality: Causality, variability: Variability) -> Variable {
    let start = (causality != Causality::Output).then_some(0.0);
    Variable {
        name: name.into(),
        vr,
        causality,
        variability,
        start,
        unit: None,
        description: String::new(),
        depends_on: Vec::new(),
    }
}

impl CoSimModel for Ramp {
    const RESOURCE: &'static str = "ramp.txt";
    const GUID_NAMESPACE: &'static str = "fmi2.test";
    const BUILD_ID: &'static str = "ramp/1";
    const GENERATION_TOOL: &'static str = "test";
    const STATE_MAGIC: [u8; 8] = *b"RAMPFMI2";

    fn from_resource(_: &str) -> Result<Self, String> {
        use Causality::*;
        use Variability::*;
        Ok(Self {
            vars: vec![
                var("u", 1, Input, Continuous),
                var("x", 2, Output, Continuous),
                var("k", 3, Parameter, Fixed),
                var("g", 4, Parameter, Tunable),
            ],
            strings: vec![
                StringVariable {
                    name: "label".into(),
                    vr: 5,
                    variability: Fixed,
                    start: "start".into(),
                    description: String::new(),
                },
                StringVariable {
                    name: "note".into(),
                    vr: 6,
                    variability: Tunable,
                    start: String::new(),
                    description: String::new(),
                },
            ],
            label: "start".into(),
            note: String::new(),
            warning: None,
            x: 0.0,
            u: 0.0,
            k: 1.0,
            g: 0.0,
        })
    }
    fn model_info(&self) -> ModelInfo {
        ModelInfo {
            model_name: "ramp".into(),
            description: String::new(),
            start_time: 0.0,
            stop_time: 1.0,
            step_size: 0.1,
            capabilities: Default::default(),
        }
    }
    fn variables(&self) -> &[Variable] {
        &self.vars
    }
    fn get_real(&self, index: usize) -> Result<f64, String> {
        Ok([self.u, self.x, self.k, self.g][index])
    }
    fn set_real(&mut self, index: usize, value: f64) -> Result<(), String> {
        match index {
            0 => self.u = value,
            2 if value < 0.0 => return Err("k must be >= 0".into()),
            2 => self.k = value,
            3 => self.g = value,
            _ => return Err("not settable".into()),
        }
        Ok(())
    }
    fn initialize(&mut self, _: f64) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _: f64, h: f64) -> Result<(), StepError> {
        if self.u.abs() > 1.0 {
            return Err(StepError::Discard(format!("|u| = {} > 1", self.u.abs())));
        }
        let x = self.x + (self.k * self.u + self.g) * h;
        if x > 100.0 {
            return Err(StepError::Terminate("x would pass 100".into()));
        }
        self.x = x;
        if self.note == "warn" {
            self.warning = Some(format!("note says warn at x = {x}"));
        }
        Ok(())
    }
    fn string_variables(&self) -> &[StringVariable] {
        &self.strings
    }
    fn get_string(&self, index: usize) -> Result<&str, String> {
        Ok([&self.label, &self.note][index])
    }
    fn set_string(&mut self, index: usize, value: &str) -> Result<(), String> {
        match index {
            0 if value == "bad" => return Err("label must not be bad".into()),
            0 => self.label = value.to_owned(),
            _ => self.note = value.to_owned(),
        }
        Ok(())
    }
    fn take_warning(&mut self) -> Option<String> {
        self.warning.take()
    }
    fn reset(&mut self) -> Result<(), String> {
        *self = Self::from_resource("")?;
        Ok(())
    }
    fn save_state(&self) -> Vec<u8> {
        [self.x, self.u, self.k, self.g]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect()
    }
    fn load_state(&mut self, b: &[u8]) -> Result<(), String> {
        if b.len() != 32 {
            return Err(format!("{} bytes, expected 32", b.len()));
        }
        let v = |i: usize| f64::from_le_bytes(b[8 * i..8 * i + 8].try_into().unwrap());
        (self.x, self.u, self.k, self.g) = (v(0), v(1), v(2), v(3));
        Ok(())
    }
}

/// An instance in `instantiated`, logging everything to memory.
fn instance() -> Instance<Ramp> {
    let model = Ramp::from_resource("").unwrap();
    Instance::new("ramp", Logger::memory(), true, "{g}".into(), model).unwrap()
}

/// An instance in `stepComplete` at t = 0.
fn initialized() -> Instance<Ramp> {
    let mut i = instance();
    assert_eq!(i.setup_experiment(None, 0.0, Some(10.0)), Status::Ok);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    i
}

fn last(i: &Instance<Ramp>) -> Message {
    i.messages().pop().expect("a message")
}

fn x(i: &Instance<Ramp>) -> f64 {
    let mut out = [f64::NAN];
    assert_eq!(i.get_real(&[2], &mut out), Status::Ok);
    out[0]
}

#[test]
fn illegal_calls_are_errors_that_change_nothing() {
    let mut i = instance();
    assert_eq!(i.do_step(0.0, 0.1), Status::Error);
    let m = last(&i);
    assert_eq!(
        (m.status, m.category),
        (Status::Error, LogCategory::StatusError)
    );
    assert!(
        m.text.contains("fmi2DoStep: illegal call sequence"),
        "{}",
        m.text
    );
    assert_eq!(i.layer.state, ModelState::INSTANTIATED);
    assert_eq!(
        i.get_real(&[2], &mut [0.0]),
        Status::Error,
        "no outputs yet"
    );
    assert_eq!(i.exit_initialization_mode(), Status::Error);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(i.setup_experiment(None, 0.0, None), Status::Error);
}

#[test]
fn set_real_is_all_or_nothing() {
    let mut i = initialized();
    assert_eq!(i.set_real(&[1], &[0.5]), Status::Ok);
    // an output, a non-finite value, a fixed parameter after initialization, a refusal
    for (vrs, vals, part) in [
        (
            &[1, 2][..],
            &[0.7, 1.0][..],
            "x (value reference 2) is an output",
        ),
        (
            &[1, 4],
            &[0.7, f64::NAN],
            "g (value reference 4) = NaN is not finite",
        ),
        (&[1, 3], &[0.7, 2.0], "fixed parameter"),
        (&[9], &[0.0], "value reference 9 is not a variable"),
    ] {
        assert_eq!(i.set_real(vrs, vals), Status::Error, "{part}");
        assert!(last(&i).text.contains(part), "{}", last(&i).text);
        assert_eq!(i.model.u, 0.5, "nothing was set");
    }
    // the model refuses the second value: the first is restored
    let mut j = instance();
    assert_eq!(j.set_real(&[4, 3], &[2.0, -1.0]), Status::Error);
    assert_eq!((j.model.g, j.model.k), (0.0, 1.0));
    assert_eq!(i.set_real(&[4], &[3.0]), Status::Ok, "tunable any time");
}

#[test]
fn a_failing_step_is_a_recoverable_discard_and_terminate_ends() {
    let mut i = initialized();
    assert_eq!(i.set_real(&[1], &[1.0]), Status::Ok);
    assert_eq!(i.do_step(0.0, 0.5), Status::Ok);
    let saved = i.get_fmu_state().unwrap();
    assert_eq!(i.set_real(&[1], &[2.0]), Status::Ok);
    assert_eq!(i.do_step(0.5, 0.5), Status::Discard);
    let m = last(&i);
    assert_eq!(m.category, LogCategory::StatusDiscard);
    assert!(m.text.contains("|u| = 2 > 1") && m.text.contains("fmi2Terminated = false"));
    assert_eq!(i.get_boolean_status(FMI2_TERMINATED), Ok(false));
    assert_eq!(i.get_real_status(FMI2_LAST_SUCCESSFUL_TIME), Ok(0.5));
    assert_eq!(i.get_status(FMI2_DO_STEP_STATUS), Ok(Status::Discard));
    assert_eq!((x(&i), i.layer.state), (0.5, ModelState::STEP_FAILED));
    assert_eq!(
        i.do_step(0.5, 0.5),
        Status::Error,
        "no DoStep in stepFailed"
    );
    // roll back and retry with a smaller input
    assert_eq!(i.set_fmu_state(&saved), Status::Ok);
    assert_eq!(i.do_step(0.5, 0.25), Status::Ok);
    assert_eq!(x(&i), 0.75);
    // a model that cannot continue: Terminated
    assert_eq!(i.set_real(&[4], &[1e3]), Status::Ok);
    assert_eq!(i.do_step(0.75, 0.25), Status::Discard);
    assert!(last(&i).text.contains("fmi2Terminated = true"));
    assert_eq!(i.get_boolean_status(FMI2_TERMINATED), Ok(true));
    assert_eq!(i.terminate(), Status::Ok);
}

#[test]
fn unavailable_status_kinds_are_discard() {
    let i = initialized();
    assert_eq!(i.get_status(FMI2_PENDING_STATUS), Err(Status::Discard));
    assert_eq!(last(&i).category, LogCategory::StatusDiscard);
    assert_eq!(i.get_real_status(FMI2_TERMINATED), Err(Status::Discard));
    assert_eq!(
        i.get_boolean_status(FMI2_DO_STEP_STATUS),
        Err(Status::Discard)
    );
    assert_eq!(
        i.get_integer_status(FMI2_LAST_SUCCESSFUL_TIME),
        Status::Discard
    );
    assert_eq!(i.get_string_status(FMI2_PENDING_STATUS), Status::Discard);
    assert_eq!(i.get_string_status(42), Status::Error, "no status kind");
    assert!(last(&i).text.contains("s = 42 is not an fmi2StatusKind"));
}

#[test]
fn step_times_are_checked() {
    let mut i = initialized();
    assert_eq!(i.do_step(0.0, 0.0), Status::Error);
    assert_eq!(i.do_step(1.0, 0.1), Status::Error);
    assert!(last(&i)
        .text
        .contains("currentCommunicationPoint = 1 differs"));
    // host-style drift is accepted, h/2 is not
    assert_eq!(i.do_step(1e-12, 0.1), Status::Ok);
    assert_eq!(i.do_step(0.1 + 0.05, 0.1), Status::Error);
    assert_eq!(i.do_step(0.1, 1e-18), Status::Error, "t + h == t");
    assert!(last(&i).text.contains("does not advance time"));
    assert_eq!(i.do_step(0.1, 10.0), Status::Error, "beyond stopTime");
    assert!(last(&i).text.contains("beyond stopTime = 10"));
}

#[test]
fn log_all_means_every_message() {
    let mut i = initialized();
    assert_eq!(i.set_debug_logging(false, &[]), Status::Ok);
    let before = i.messages().len();
    assert_eq!(i.do_step(5.0, 0.1), Status::Error);
    assert_eq!(i.messages().len(), before, "all off");
    assert_eq!(i.set_debug_logging(true, &["logAll"]), Status::Ok);
    assert_eq!(i.do_step(5.0, 0.1), Status::Error);
    assert_eq!(last(&i).category, LogCategory::StatusError);
    assert_eq!(i.set_debug_logging(true, &["logNothing"]), Status::Error);
    assert!(last(&i)
        .text
        .contains("\"logNothing\" is not a log category"));
}

#[test]
fn fmu_states_serialize_and_free() {
    let mut i = initialized();
    assert_eq!(i.set_real(&[1], &[0.5]), Status::Ok);
    assert_eq!(i.do_step(0.0, 0.2), Status::Ok);
    let s = i.get_fmu_state().unwrap();
    let n = i.serialized_fmu_state_size(&s).unwrap();
    let mut bytes = vec![0 as fmi2Byte; n];
    assert_eq!(
        i.serialize_fmu_state(&s, &mut bytes[..n - 1]),
        Status::Error
    );
    assert_eq!(i.serialize_fmu_state(&s, &mut bytes), Status::Ok);
    let bytes: Vec<u8> = bytes.iter().map(|b| *b as u8).collect();
    assert_eq!(i.deserialize_fmu_state(&bytes), Ok(s.clone()));
    let mut other = Instance::new(
        "other",
        Logger::memory(),
        false,
        "{h}".into(),
        Ramp::from_resource("").unwrap(),
    )
    .unwrap();
    assert_eq!(
        other.deserialize_fmu_state(&bytes),
        Err(Status::Error),
        "other GUID"
    );
    // free: kept on an illegal call (fatal), taken otherwise
    let mut owned = Some(Box::new(s));
    i.layer.state = ModelState::FATAL;
    assert_eq!(i.free_fmu_state(&mut owned), Status::Error);
    assert!(owned.is_some());
    i.layer.state = ModelState::STEP_COMPLETE;
    assert_eq!(i.free_fmu_state(&mut owned), Status::Ok);
    assert!(owned.is_none());
    assert_eq!(other.reset(), Status::Ok);
}

#[test]
fn getters_never_answer_a_non_finite_number_with_ok() {
    // a model whose state holds infinity (Ramp's load_state takes any bits): the layer refuses
    // to report it, whatever the model says
    let mut i = initialized();
    let mut s = i.get_fmu_state().unwrap();
    s.model[..8].copy_from_slice(&f64::INFINITY.to_le_bytes());
    assert_eq!(i.set_fmu_state(&s), Status::Ok);
    let mut out = [0.0, 0.0];
    assert_eq!(i.get_real(&[1, 2], &mut out), Status::Error);
    let m = last(&i);
    assert!(
        m.text.contains("x (value reference 2) = inf is not finite"),
        "{m:?}"
    );
    // the finite ones still read
    assert_eq!(i.get_real(&[1], &mut out[..1]), Status::Ok);
}

/// The values of `vrs` by fmi2GetString, read back from the instance's copies.
fn strings(i: &mut Instance<Ramp>, vrs: &[u32]) -> Vec<String> {
    let mut out = vec![std::ptr::null(); vrs.len()];
    assert_eq!(i.get_string(vrs, &mut out), Status::Ok);
    // the pointers are those of the instance's copies (valid until the next fmi2GetString)
    for (p, c) in out.iter().zip(i.last_strings()) {
        assert_eq!(*p, c.as_ptr());
    }
    i.last_strings()
        .iter()
        .map(|c| c.to_str().unwrap().to_owned())
        .collect()
}

#[test]
fn string_parameters_get_and_set() {
    let mut i = instance();
    // set in instantiated, read from initialization mode on (FMI 2.0's table)
    assert_eq!(i.set_string(&[5, 6], &["a/b", "n"]), Status::Ok);
    assert_eq!(i.get_string(&[5], &mut [std::ptr::null()]), Status::Error);
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(strings(&mut i, &[6, 5, 5]), ["n", "a/b", "a/b"]);
    assert_eq!(i.set_string(&[], &[]), Status::Ok);
    // all or nothing: a refused value restores those set before it
    assert_eq!(i.set_string(&[6, 5], &["m", "bad"]), Status::Error);
    assert!(last(&i)
        .text
        .contains("label must not be bad; nothing was set"));
    assert_eq!(strings(&mut i, &[5, 6]), ["a/b", "n"]);
    // unknown and wrong-type value references
    assert_eq!(i.set_string(&[99], &["x"]), Status::Error);
    assert!(last(&i)
        .text
        .contains("value reference 99 is not a variable"));
    assert_eq!(i.set_string(&[3], &["x"]), Status::Error);
    assert!(last(&i)
        .text
        .contains("is k, a Real variable, not a String"));
    let mut out = [std::ptr::null(); 1];
    assert_eq!(i.get_string(&[2], &mut out), Status::Error);
    assert!(out[0].is_null(), "out unchanged on error");
    assert!(last(&i)
        .text
        .contains("is x, a Real variable, not a String"));
    let mut real = [0.0];
    assert_eq!(i.get_real(&[5], &mut real), Status::Error);
    assert!(last(&i)
        .text
        .contains("is label, a String variable, not a Real"));
    assert_eq!(i.set_real(&[6], &[1.0]), Status::Error);
    assert_eq!(i.get_integer(&[5], &mut [0]), Status::Error);
    assert!(last(&i).text.contains("only Real and String variables"));
    // fixed: not after fmi2ExitInitializationMode; tunable: any time
    assert_eq!(i.set_string(&[5], &["init"]), Status::Ok);
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    assert_eq!(i.set_string(&[5], &["late"]), Status::Error);
    assert!(last(&i)
        .text
        .contains("label (value reference 5) is a fixed parameter"));
    assert_eq!(i.set_string(&[6], &["late"]), Status::Ok);
    assert_eq!(strings(&mut i, &[5, 6]), ["init", "late"]);
}

#[test]
fn string_parameters_travel_with_the_fmu_state() {
    let mut i = instance();
    assert_eq!(i.enter_initialization_mode(), Status::Ok);
    assert_eq!(strings(&mut i, &[5, 6]), ["start", ""]);
    assert_eq!(i.exit_initialization_mode(), Status::Ok);
    assert_eq!(i.set_string(&[6], &["first"]), Status::Ok);
    let s = i.get_fmu_state().unwrap();
    assert_eq!(s.strings, ["start", "first"]);
    let bytes = s.serialize(b"RAMPFMI2", &i.guid);
    assert_eq!(i.set_string(&[6], &["second"]), Status::Ok);
    let t = i.deserialize_fmu_state(&bytes).unwrap();
    assert_eq!(t.strings, s.strings);
    assert_eq!(i.set_fmu_state(&t), Status::Ok);
    assert_eq!(strings(&mut i, &[6]), ["first"]);
    // a refused model state sets the String values back
    assert_eq!(i.set_string(&[6], &["third"]), Status::Ok);
    let mut bad = s.clone();
    bad.model.pop();
    assert_eq!(i.set_fmu_state(&bad), Status::Error);
    assert_eq!(strings(&mut i, &[6]), ["third"]);
}

#[test]
fn a_model_warning_makes_the_call_a_warning() {
    let mut i = initialized();
    assert_eq!(i.do_step(0.0, 0.1), Status::Ok);
    assert_eq!(i.set_string(&[6], &["warn"]), Status::Ok);
    assert_eq!(i.do_step(0.1, 0.1), Status::Warning);
    let m = last(&i);
    assert_eq!(m.status, Status::Warning);
    assert_eq!(m.category, LogCategory::StatusWarning);
    assert!(
        m.text.starts_with("fmi2DoStep: note says warn"),
        "{}",
        m.text
    );
    assert_eq!(i.get_status(FMI2_DO_STEP_STATUS), Ok(Status::Warning));
    // the step was taken
    assert_eq!(i.get_real_status(FMI2_LAST_SUCCESSFUL_TIME), Ok(0.2));
    assert_eq!(i.set_string(&[6], &[""]), Status::Ok);
    assert_eq!(i.do_step(0.2, 0.1), Status::Ok);
}
