//! Log categories (declared in modelDescription.xml) and where an instance's messages go.
//!
//! The FMI 2.0 logger is a C-variadic, printf-style function. This layer always calls it with
//! the fixed format `"%s"` and the message as the one argument, so text from users or models is
//! never interpreted as a format (the call itself is in [`guard`](crate::guard)).
//!
//! Filtering: each category has an on/off flag. At fmi2Instantiate the four status categories are
//! on and `logAll` follows `loggingOn`. fmi2SetDebugLogging(on, 0, NULL) sets every category to
//! `on`; with a list it sets only the listed ones. `logAll` means "all messages" (FMI 2.0
//! §2.2.4): a message is sent iff its own category or `logAll` is on. The call trace has no
//! category of its own: it is sent iff `logAll` is on.

use std::cell::RefCell;
use std::ffi::{CStr, CString};

use super::guard::{self, HostCallbacks};
use super::types::Status;

/// A log category of this FMU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LogCategory {
    /// Warnings.
    StatusWarning,
    /// Steps that returned fmi2Discard.
    StatusDiscard,
    /// Errors: illegal calls, bad arguments, model failures.
    StatusError,
    /// Fatal errors (internal faults).
    StatusFatal,
    /// All messages: every status category and the trace of every call with its arguments.
    All,
}

impl LogCategory {
    /// Every category, in the order of the XML.
    pub const ALL: [LogCategory; 5] = [
        LogCategory::StatusWarning,
        LogCategory::StatusDiscard,
        LogCategory::StatusError,
        LogCategory::StatusFatal,
        LogCategory::All,
    ];

    /// The category name as it appears in the XML and the logger calls.
    pub const fn c_name(self) -> &'static CStr {
        match self {
            LogCategory::StatusWarning => c"logStatusWarning",
            LogCategory::StatusDiscard => c"logStatusDiscard",
            LogCategory::StatusError => c"logStatusError",
            LogCategory::StatusFatal => c"logStatusFatal",
            LogCategory::All => c"logAll",
        }
    }

    /// The category name as a Rust string.
    pub fn name(self) -> &'static str {
        // The literals above are ASCII.
        self.c_name().to_str().unwrap_or("logAll")
    }

    /// The category's description in the XML.
    pub const fn description(self) -> &'static str {
        match self {
            LogCategory::StatusWarning => "Warnings",
            LogCategory::StatusDiscard => "Communication steps refused with fmi2Discard",
            LogCategory::StatusError => {
                "Errors: illegal call sequences, invalid arguments, model failures"
            }
            LogCategory::StatusFatal => "Fatal internal faults",
            LogCategory::All => "All messages: every status category and the trace of every call",
        }
    }

    /// The index of the category in [`LogCategory::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// The category by name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The category of a message with this status (`All` for fmi2OK).
    pub const fn for_status(status: Status) -> Self {
        match status {
            Status::Ok => LogCategory::All,
            Status::Warning => LogCategory::StatusWarning,
            Status::Discard => LogCategory::StatusDiscard,
            Status::Error => LogCategory::StatusError,
            Status::Fatal => LogCategory::StatusFatal,
        }
    }
}

/// The enabled categories of one instance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LogFilter([bool; 5]);

impl LogFilter {
    /// Status categories on, `logAll` = `logging_on`.
    pub const fn new(logging_on: bool) -> Self {
        Self([true, true, true, true, logging_on])
    }

    /// True if messages of `category` are sent: its own flag or `logAll` is on.
    #[inline]
    pub const fn enabled(&self, category: LogCategory) -> bool {
        self.0[category.index()] || self.0[LogCategory::All.index()]
    }

    /// Turns one category on or off.
    pub fn set(&mut self, category: LogCategory, on: bool) {
        self.0[category.index()] = on;
    }

    /// Turns every category on or off.
    pub fn set_all(&mut self, on: bool) {
        self.0 = [on; 5];
    }
}

/// A C string of `text` (interior NUL bytes are replaced by `?`).
pub fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', "?")).unwrap_or_default()
}

/// One message as a logger receives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    /// Status of the message.
    pub status: Status,
    /// Category of the message.
    pub category: LogCategory,
    /// The text.
    pub text: String,
}

/// Where an instance's messages go.
#[derive(Debug)]
pub enum Logger {
    /// The host's callbacks, copied by value at fmi2Instantiate (the host may free its struct);
    /// a NULL logger drops every message.
    Host(HostCallbacks),
    /// Kept in memory: for Rust hosts and tests that drive [`Instance`](crate::Instance)
    /// without a C logger.
    Memory(RefCell<Vec<Message>>),
}

impl Logger {
    /// An empty in-memory logger.
    pub fn memory() -> Self {
        Logger::Memory(RefCell::new(Vec::new()))
    }

    /// Sends one message.
    pub fn send(&self, instance_name: &CStr, status: Status, category: LogCategory, text: &str) {
        match self {
            Logger::Host(callbacks) => {
                guard::call_logger(callbacks, instance_name, status, category, text)
            }
            Logger::Memory(messages) => messages.borrow_mut().push(Message {
                status,
                category,
                text: text.to_owned(),
            }),
        }
    }

    /// The messages kept so far (empty for a host logger).
    pub fn messages(&self) -> Vec<Message> {
        match self {
            Logger::Host(_) => Vec::new(),
            Logger::Memory(messages) => messages.borrow().clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_filter() {
        for c in LogCategory::ALL {
            assert_eq!(LogCategory::from_name(c.name()), Some(c));
        }
        let mut f = LogFilter::new(false);
        assert!(f.enabled(LogCategory::StatusError) && !f.enabled(LogCategory::All));
        f.set(LogCategory::All, true);
        assert!(f.enabled(LogCategory::All));
        f.set_all(false);
        f.set(LogCategory::All, true);
        assert!(
            f.enabled(LogCategory::StatusError),
            "logAll means all messages"
        );
        f.set(LogCategory::All, false);
        assert!(!f.enabled(LogCategory::StatusError));
        assert_eq!(c_string("a\0b").to_str().unwrap(), "a?b");
    }
}
