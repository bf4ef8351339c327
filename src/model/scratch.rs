//! [`Scratch`]: working memory that an evaluation through `&self` reuses (a residual for the
//! outputs, a station's loads): sized once, then borrowed per call without allocating. Each
//! model instance owns its own; the lock is uncontended (an instance is stepped by one thread at
//! a time), so it costs an atomic exchange, never a system call or an allocation.

use std::sync::Mutex;

/// Reusable working memory `T` behind a lock.
#[derive(Debug, Default)]
pub struct Scratch<T>(Mutex<T>);

impl<T> Scratch<T> {
    /// Holds `value`.
    pub fn new(value: T) -> Self {
        Self(Mutex::new(value))
    }

    /// Calls `f` with the memory (a panic that poisoned the lock left it in a state `f` must
    /// overwrite anyway: working memory carries nothing between calls).
    pub fn with<R>(&self, f: impl FnOnce(&mut T) -> R) -> R {
        let mut guard = self.0.lock().unwrap_or_else(|e| e.into_inner());
        f(&mut guard)
    }
}

impl<T: Default> Scratch<T> {
    /// Takes the memory out (a default in its place) for a computation with several exits;
    /// [`Scratch::put`] returns it (memory not returned is only allocated again next time).
    pub fn take(&self) -> T {
        self.with(std::mem::take)
    }

    /// Returns memory taken by [`Scratch::take`].
    pub fn put(&self, value: T) {
        self.with(|t| *t = value);
    }
}

impl<T: Clone> Clone for Scratch<T> {
    fn clone(&self) -> Self {
        Self::new(self.with(|t| t.clone()))
    }
}
