//! Ctrl-C and SIGTERM: the end every long-running command shares.

use anyhow::Context as _;

/// Ctrl-C, or SIGTERM on Unix. Nothing needs flushing: every acknowledged
/// write is already on disk.
pub async fn shutdown_signal() {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{SignalKind, signal};
        match signal(SignalKind::terminate()) {
            Ok(mut term) => {
                tokio::select! {
                    _ = tokio::signal::ctrl_c() => {}
                    _ = term.recv() => {}
                }
            }
            Err(_) => {
                let _ = tokio::signal::ctrl_c().await;
            }
        }
    }
    #[cfg(not(unix))]
    {
        let _ = tokio::signal::ctrl_c().await;
    }
}

/// Calls `then` on a thread of its own when Ctrl-C or SIGTERM arrives.
///
/// # Errors
/// The watcher could not be started.
pub fn on_signal(then: impl FnOnce() + Send + 'static) -> anyhow::Result<()> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .context("cannot start the signal watcher")?;
    std::thread::Builder::new()
        .name("ecam-signals".into())
        .spawn(move || {
            runtime.block_on(shutdown_signal());
            then();
        })
        .context("cannot start the signal watcher")?;
    Ok(())
}
