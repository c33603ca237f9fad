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
//! by [`compiled_here`] into their `impl Scalar` blocks, are ordinary
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

/// The hidden entry methods of [`crate::Scalar`] for one concrete type:
/// each calls the generic implementation for `Self`, which is thereby
/// instantiated in this crate.
macro_rules! compiled_here {
    () => {
        #[inline(never)]
        fn entry_solve(
            problem: &crate::Plcp<Self>,
            settings: &crate::Settings<Self>,
        ) -> Result<crate::Path<Self>, crate::PlcpError> {
            crate::solve_here(problem, settings)
        }
        #[inline(never)]
        fn entry_certify_escalating(
            problem: &crate::Plcp<Self>,
            settings: &crate::Settings<Self>,
            path: &mut crate::Path<Self>,
        ) -> crate::exact::Certificate {
            crate::escalate::certify_escalating(problem, settings, path)
        }
        #[inline(never)]
        fn entry_certify_with(
            problem: &crate::Plcp<Self>,
            path: &crate::Path<Self>,
            engine: crate::exact::Engine,
        ) -> crate::exact::Certificate {
            crate::exact::certify_here(problem, path, engine)
        }
        #[inline(never)]
        fn entry_exact_trace(
            problem: &crate::Plcp<Self>,
            settings: &crate::Settings<Self>,
        ) -> Result<crate::exact::ExactPath, crate::PlcpError> {
            crate::exact::trace_here(problem, settings)
        }
        #[inline(never)]
        fn entry_exact_trace_from(
            problem: &crate::Plcp<Self>,
            settings: &crate::Settings<Self>,
            basis: &[crate::Var],
            lambda: Self,
        ) -> Result<crate::exact::ExactPath, crate::PlcpError> {
            crate::exact::trace_from_here(problem, settings, basis, lambda)
        }
        #[inline(never)]
        fn entry_solve_lcp(
            lcp: &crate::Lcp<Self>,
            settings: &crate::Settings<Self>,
        ) -> Result<crate::LcpSolution<Self>, crate::PlcpError> {
            crate::lemke::solve_lcp_here(lcp, settings)
        }
        #[inline(never)]
        fn entry_principal_measured(
            problem: &crate::Plcp<Self>,
            settings: &crate::Settings<Self>,
        ) -> Result<crate::Path<Self>, &'static str> {
            crate::trace::principal_measured_here(problem, settings)
        }
        #[inline(never)]
        fn entry_solver_path(
            solver: &mut crate::Solver<'_, Self>,
            q: faer::ColRef<'_, Self>,
            d: faer::ColRef<'_, Self>,
            lambda_max: Self,
        ) -> Result<crate::Path<Self>, crate::PlcpError> {
            solver.path_here(q, d, lambda_max)
        }
        #[inline(never)]
        fn entry_solver_path_end(
            solver: &mut crate::Solver<'_, Self>,
            q: faer::ColRef<'_, Self>,
            d: faer::ColRef<'_, Self>,
            lambda_max: Self,
        ) -> Result<(), crate::PlcpError> {
            solver.path_end_here(q, d, lambda_max)
        }
    };
}
pub(crate) use compiled_here;
