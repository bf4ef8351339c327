//! [`export_fmi2!`](crate::export_fmi2): the 34 `extern "C"` FMI 2.0 co-simulation symbols,
//! generated from the one function table ([`state`](crate::state)). Each symbol forwards to
//! the function of the same name in [`guard`](crate::guard), and a compile-time check compares
//! its signature with the binding of the official header ([`sys`](crate::sys)).

/// Exports the 34 FMI 2.0 co-simulation functions (`fmi2Instantiate`, `fmi2DoStep`, ...) as
/// `#[no_mangle] extern "C"` symbols driving the model type `$model` (a
/// [`CoSimModel`](crate::CoSimModel)), in a module `fmi2_exports` of the calling crate. Use it
/// once per shared library.
#[macro_export]
macro_rules! export_fmi2 {
    ($model:ty) => {
        /// The model the FMI 2.0 symbols of this library drive.
        type __Fmi2Model = $model;

        /// The 34 FMI 2.0 co-simulation symbols of this library (`export_fmi2!`).
        pub mod fmi2_exports {
            #[allow(unused_imports)]
            use $crate::types::*;
            #[allow(unused_imports)]
            use ::std::ffi::c_char;

            $crate::__fmi2_function_table!($crate::__fmi2_shims { [super::__Fmi2Model] });
        }
    };
}

/// The shims of [`export_fmi2!`] from the function table.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_shims {
    ([$model:path]
     $($variant:ident $name:ident $ty:ident $mask:ident
       ($($p:ident: $t:ty),* $(,)?) -> $ret:ty;)*) => {
        $(
            #[doc = concat!("FMI 2.0 `", stringify!($name), "`: forwards to `fmi2::guard::",
                stringify!($name), "`.")]
            #[doc = ""]
            #[doc = "# Safety"]
            #[doc = "The FMI 2.0 calling contract (see `fmi2::guard`)."]
            #[no_mangle]
            pub unsafe extern "C" fn $name($($p: $t),*) -> $ret {
                // SAFETY: the host's FMI 2.0 calling contract, forwarded.
                #[allow(unused_unsafe)]
                unsafe {
                    $crate::__fmi2_forward!($name, $model, ($($p),*))
                }
            }
            const _: $crate::types::sys::$ty = Some($name);
        )*
    };
}

/// The call of one shim into [`guard`](crate::guard): generic over the model except for the
/// two functions without an instance.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_forward {
    (fmi2GetTypesPlatform, $model:path, ()) => {
        $crate::guard::fmi2GetTypesPlatform()
    };
    (fmi2GetVersion, $model:path, ()) => {
        $crate::guard::fmi2GetVersion()
    };
    ($name:ident, $model:path, ($($p:ident),*)) => {
        $crate::guard::$name::<$model>($($p),*)
    };
}
