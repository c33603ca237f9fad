//! The examples' standard output: written through a locked handle with
//! `writeln!`, so that a reader that closes the pipe early (`| head -1`)
//! ends the example quietly, where `println!` panics on the broken pipe.

use std::error::Error;
use std::io::{ErrorKind, StdoutLock, Write};

/// Runs `body` on the locked stdout (flushed at its end); a broken pipe
/// ends it quietly (`Ok`), any other error is passed on.
pub fn run(
    body: impl FnOnce(&mut StdoutLock<'static>) -> Result<(), Box<dyn Error>>,
) -> Result<(), Box<dyn Error>> {
    let mut out = std::io::stdout().lock();
    match body(&mut out).and_then(|()| Ok(out.flush()?)) {
        Err(e)
            if e.downcast_ref::<std::io::Error>()
                .is_some_and(|e| e.kind() == ErrorKind::BrokenPipe) =>
        {
            Ok(())
        }
        r => r,
    }
}
