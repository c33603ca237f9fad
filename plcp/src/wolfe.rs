//! (in progress)
pub(crate) fn solve<T: crate::Scalar>(_p: &crate::Plcp<T>, _s: &crate::Settings<T>) -> Result<crate::Path<T>, crate::PlcpError> { todo!() }
