//! The entry points compiled once, here, for `f32`, `f64` and `fx128`.
//!
//! Rust compiles a generic function again in every crate that calls it with
//! a concrete type: an optimised build shares no generic code between
//! crates. Each binary that called `plcp::solve::<f64>` (every example, test
//! and user program) therefore compiled the whole engine anew, faer's
//! factorisations with it: about a minute of release build a binary.
//!
//! So the public entry points are thin generic wrappers that call a hidden
//! method of [`Scalar`]. Its implementations for the three types, written
//! by [`entry_points`] into their `impl Scalar` blocks, are ordinary
//! functions of this crate, compiled with it and only linked by the caller
//! (`#[inline(never)]`, so that no caller inlines them and instantiates the
//! engine after all). A test or example binary now builds in seconds, not in
//! a minute (`principal_check`, release: 50.6 s before, 3.2 s after).
//!
//! The hidden methods have no default bodies, so [`Scalar`] is implemented
//! for these three types only (it always said so). A new entry point whose
//! body instantiates much of the engine gets a method here too.
//!
//! [`Scalar`]: crate::Scalar

/// The entry points, listed once: `entry_points!(declare)` writes them into
/// [`crate::Scalar`] as hidden required methods, `entry_points!(define)`
/// into the `impl Scalar` of each of the three types, `#[inline(never)]`,
/// each calling the generic body for `Self`, which is thereby instantiated
/// in this crate.
macro_rules! entry_points {
    ($mode:ident) => {
        crate::entry::entry_points! { @$mode
            /// [`crate::solve`].
            fn entry_solve(
                problem: &crate::Plcp<Self>,
                settings: &crate::Settings<Self>,
            ) -> Result<crate::Path<Self>, crate::PlcpError> =
                crate::solve_here(problem, settings);
            /// The certification of [`crate::solve_certified`].
            fn entry_certify_escalating(
                problem: &crate::Plcp<Self>,
                settings: &crate::Settings<Self>,
                path: &mut crate::Path<Self>,
            ) -> crate::exact::Certificate =
                crate::escalate::certify_escalating(problem, settings, path);
            /// [`crate::exact::certify_with`].
            fn entry_certify_with(
                problem: &crate::Plcp<Self>,
                path: &crate::Path<Self>,
                engine: crate::exact::Engine,
            ) -> crate::exact::Certificate =
                crate::exact::certify_here(problem, path, engine);
            /// [`crate::exact::trace`].
            fn entry_exact_trace(
                problem: &crate::Plcp<Self>,
                settings: &crate::Settings<Self>,
            ) -> Result<crate::exact::ExactPath, crate::PlcpError> =
                crate::exact::trace_here(problem, settings);
            /// [`crate::exact::trace_from`].
            fn entry_exact_trace_from(
                problem: &crate::Plcp<Self>,
                settings: &crate::Settings<Self>,
                basis: &[crate::Var],
                lambda: Self,
            ) -> Result<crate::exact::ExactPath, crate::PlcpError> =
                crate::exact::trace_from_here(problem, settings, basis, lambda);
            /// [`crate::solve_lcp`].
            fn entry_solve_lcp(
                lcp: &crate::Lcp<Self>,
                settings: &crate::Settings<Self>,
            ) -> Result<crate::LcpSolution<Self>, crate::PlcpError> =
                crate::lemke::solve_lcp_here(lcp, settings);
            /// The fast path of [`crate::solve_observed`].
            fn entry_principal_measured(
                problem: &crate::Plcp<Self>,
                settings: &crate::Settings<Self>,
            ) -> Result<crate::Path<Self>, &'static str> =
                crate::trace::principal_measured_here(problem, settings);
            /// [`crate::Solver::path`] (and `lcp`, `step`).
            fn entry_solver_path(
                solver: &mut crate::Solver<'_, Self>,
                q: faer::ColRef<'_, Self>,
                d: faer::ColRef<'_, Self>,
                lambda_max: Self,
            ) -> Result<crate::Path<Self>, crate::PlcpError> =
                solver.path_here(q, d, lambda_max);
            /// [`crate::Solver::path_end`] (and `lcp_end`, `step_end`).
            fn entry_solver_path_end(
                solver: &mut crate::Solver<'_, Self>,
                q: faer::ColRef<'_, Self>,
                d: faer::ColRef<'_, Self>,
                lambda_max: Self,
            ) -> Result<(), crate::PlcpError> =
                solver.path_end_here(q, d, lambda_max);
        }
    };
    (@declare $(
        $(#[$doc:meta])*
        fn $name:ident($($arg:ident: $ty:ty),* $(,)?) -> $ret:ty = $body:expr;
    )*) => {
        $(
            $(#[$doc])*
            #[doc(hidden)]
            fn $name($($arg: $ty),*) -> $ret;
        )*
    };
    (@define $(
        $(#[$doc:meta])*
        fn $name:ident($($arg:ident: $ty:ty),* $(,)?) -> $ret:ty = $body:expr;
    )*) => {
        $(
            #[inline(never)]
            fn $name($($arg: $ty),*) -> $ret {
                $body
            }
        )*
    };
}
pub(crate) use entry_points;
