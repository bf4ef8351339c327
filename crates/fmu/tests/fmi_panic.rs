//! The generic entry points with a misbehaving test model, chosen by its scene text: `panic`
//! panics in do_step (caught, logged as fmi2Fatal, state `fatal`, only FreeInstance allowed,
//! nothing unwinds); `terminate` ends with [`StepError::Terminate`] (fmi2Discard with
//! fmi2Terminated = true).

mod host;

use std::ffi::{c_void, CString};

use fmi2::guard;
use fmi2::types::{
    fmi2CallbackFunctions, fmi2Component, FMI2_FALSE, FMI2_LAST_SUCCESSFUL_TIME, FMI2_TERMINATED,
    FMI2_TRUE,
};
use fmi2::{Causality, CoSimModel, ModelInfo, StepError, Variability, Variable};
use host::{file_uri, resources_with, test_logger, Callbacks, Log, DISCARD, FATAL, OK};

struct Panicky {
    vars: Vec<Variable>,
    /// Ends with StepError::Terminate instead of panicking.
    terminate: bool,
}

impl CoSimModel for Panicky {
    const RESOURCE: &'static str = "scene.toml";
    const GUID_NAMESPACE: &'static str = "test.panicky";
    const BUILD_ID: &'static str = "panicky/1";
    const GENERATION_TOOL: &'static str = "test";
    const STATE_MAGIC: [u8; 8] = *b"PANICKY1";

    fn from_resource(scene: &str) -> Result<Self, String> {
        Ok(Self {
            terminate: scene == "terminate",
            vars: vec![Variable {
                name: "y".into(),
                vr: 0,
                causality: Causality::Output,
                variability: Variability::Continuous,
                start: None,
                unit: None,
                description: String::new(),
                depends_on: Vec::new(),
            }],
        })
    }
    fn model_info(&self) -> ModelInfo {
        ModelInfo {
            model_name: "panicky".into(),
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
    fn get_real(&self, _: usize) -> Result<f64, String> {
        Ok(0.0)
    }
    fn set_real(&mut self, _: usize, _: f64) -> Result<(), String> {
        Ok(())
    }
    fn initialize(&mut self, _: f64) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _: f64, _: f64) -> Result<(), StepError> {
        if self.terminate {
            return Err(StepError::Terminate("the model reached its end".into()));
        }
        panic!("model bug in do_step")
    }
    fn reset(&mut self) -> Result<(), String> {
        Ok(())
    }
    fn save_state(&self) -> Vec<u8> {
        Vec::new()
    }
    fn load_state(&mut self, _: &[u8]) -> Result<(), String> {
        Ok(())
    }
}

/// An initialized instance of `Panicky` built from `scene`, with its log.
unsafe fn initialized(scene: &str) -> (fmi2Component, Box<Log>) {
    let log = Box::new(Log::default());
    let callbacks = Callbacks {
        logger: Some(test_logger),
        allocate_memory: None,
        free_memory: None,
        step_finished: None,
        component_environment: &*log as *const Log as *mut c_void,
    };
    let name = CString::new("panicky").unwrap();
    let guid = CString::new(fmi2::guid::guid::<Panicky>(scene.as_bytes())).unwrap();
    let location = CString::new(file_uri(&resources_with(scene, "panic"))).unwrap();
    unsafe {
        let c = guard::fmi2Instantiate::<Panicky>(
            name.as_ptr(),
            1,
            guid.as_ptr(),
            location.as_ptr(),
            &callbacks as *const Callbacks as *const fmi2CallbackFunctions,
            0,
            0,
        );
        assert!(!c.is_null(), "{:?}", log.entries());
        assert_eq!(guard::fmi2EnterInitializationMode::<Panicky>(c), OK);
        assert_eq!(guard::fmi2ExitInitializationMode::<Panicky>(c), OK);
        (c, log)
    }
}

#[test]
fn panic_in_do_step_is_fatal_not_an_unwind() {
    unsafe {
        let (c, log) = initialized("panic");
        assert_eq!(guard::fmi2DoStep::<Panicky>(c, 0.0, 0.1, 0), FATAL);
        log.assert_last(
            FATAL,
            "logStatusFatal",
            &["fmi2DoStep", "panic: model bug in do_step"],
        );
        // Fatal: every other call is refused, FreeInstance still frees.
        assert_eq!(guard::fmi2Terminate::<Panicky>(c), host::ERROR);
        guard::fmi2FreeInstance::<Panicky>(c);
    }
}

#[test]
fn terminate_error_is_discard_with_terminated_true() {
    unsafe {
        let (c, log) = initialized("terminate");
        assert_eq!(guard::fmi2DoStep::<Panicky>(c, 0.0, 0.1, 0), DISCARD);
        log.assert_last(
            DISCARD,
            "logStatusDiscard",
            &["reached its end", "fmi2Terminated = true"],
        );
        let mut terminated = FMI2_FALSE;
        assert_eq!(
            guard::fmi2GetBooleanStatus::<Panicky>(c, FMI2_TERMINATED, &mut terminated),
            OK
        );
        assert_eq!(terminated, FMI2_TRUE);
        let mut last = f64::NAN;
        assert_eq!(
            guard::fmi2GetRealStatus::<Panicky>(c, FMI2_LAST_SUCCESSFUL_TIME, &mut last),
            OK
        );
        assert_eq!(last, 0.0);
        assert_eq!(guard::fmi2Terminate::<Panicky>(c), OK);
        guard::fmi2FreeInstance::<Panicky>(c);
    }
}
