//! What the harness asks of the operating system: the calling thread's CPU time, pinning to
//! one core, locking memory. Linux only (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`,
//! `sched_setaffinity`, `mlockall`); elsewhere each call says so.

/// `clock_gettime(clock)` [ns]; panics if the kernel refuses the clock (no allocation).
#[cfg(target_os = "linux")]
#[inline]
fn clock_ns(clock: libc::clockid_t, name: &str) -> u64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid out-pointer for the call.
    let r = unsafe { libc::clock_gettime(clock, &mut ts) };
    assert_eq!(r, 0, "clock_gettime({name}) failed");
    ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64
}

/// The calling thread's CPU time (user + system) [ns], `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`.
///
/// Called twice per step inside the measured loop: no allocation, no error path but a panic on a
/// clock the kernel refuses (checked once by [`check_thread_clock`] before the loop).
#[cfg(target_os = "linux")]
#[inline]
pub fn thread_cpu_ns() -> u64 {
    clock_ns(libc::CLOCK_THREAD_CPUTIME_ID, "CLOCK_THREAD_CPUTIME_ID")
}

/// Elsewhere: no thread CPU clock (the harness refuses to start, see [`check_thread_clock`]).
#[cfg(not(target_os = "linux"))]
pub fn thread_cpu_ns() -> u64 {
    0
}

/// CLOCK_MONOTONIC now [ns] (the clock of `std::time::Instant` on Linux and of
/// [`sleep_until_ns`]).
#[cfg(target_os = "linux")]
#[inline]
pub fn monotonic_ns() -> u64 {
    clock_ns(libc::CLOCK_MONOTONIC, "CLOCK_MONOTONIC")
}

/// Elsewhere: the standard library's monotonic clock from its first use.
#[cfg(not(target_os = "linux"))]
pub fn monotonic_ns() -> u64 {
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_nanos() as u64
}

/// Sleeps until CLOCK_MONOTONIC reaches `deadline` [ns] (clock_nanosleep, TIMER_ABSTIME;
/// returns at once if it has passed). No allocation.
#[cfg(target_os = "linux")]
#[inline]
pub fn sleep_until_ns(deadline: u64) {
    let ts = libc::timespec {
        tv_sec: (deadline / 1_000_000_000) as libc::time_t,
        tv_nsec: (deadline % 1_000_000_000) as libc::c_long,
    };
    // an interrupted sleep (EINTR) sleeps again to the same deadline
    // SAFETY: a valid timespec; no remaining-time pointer with TIMER_ABSTIME.
    while unsafe {
        libc::clock_nanosleep(
            libc::CLOCK_MONOTONIC,
            libc::TIMER_ABSTIME,
            &ts,
            std::ptr::null_mut(),
        )
    } == libc::EINTR
    {}
}

/// Elsewhere: std's sleep for the remaining time.
#[cfg(not(target_os = "linux"))]
pub fn sleep_until_ns(deadline: u64) {
    let now = monotonic_ns();
    if deadline > now {
        std::thread::sleep(std::time::Duration::from_nanos(deadline - now));
    }
}

/// Checks that the thread CPU clock works, and returns its resolution [ns].
#[cfg(target_os = "linux")]
pub fn check_thread_clock() -> Result<u64, String> {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: a valid out-pointer for the call.
    let r = unsafe { libc::clock_getres(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    if r != 0 {
        return Err(format!(
            "clock_getres(CLOCK_THREAD_CPUTIME_ID) failed: {}",
            std::io::Error::last_os_error()
        ));
    }
    Ok(ts.tv_sec as u64 * 1_000_000_000 + ts.tv_nsec as u64)
}

/// Elsewhere: refused.
#[cfg(not(target_os = "linux"))]
pub fn check_thread_clock() -> Result<u64, String> {
    Err("hybeam-realtime measures thread CPU time with clock_gettime(CLOCK_THREAD_CPUTIME_ID): Linux only".into())
}

/// `Ok` for a libc call that returned 0; otherwise "`what` refused: <the OS error> (`hint`)".
#[cfg(target_os = "linux")]
fn os_result(r: libc::c_int, what: &str, hint: &str) -> Result<(), String> {
    if r == 0 {
        Ok(())
    } else {
        Err(format!(
            "{what} refused: {} ({hint})",
            std::io::Error::last_os_error()
        ))
    }
}

/// Pins the calling thread to `cpu` (sched_setaffinity).
#[cfg(target_os = "linux")]
pub fn pin_to(cpu: usize) -> Result<(), String> {
    if cpu >= libc::CPU_SETSIZE as usize {
        return Err(format!("--pin {cpu}: beyond CPU_SETSIZE"));
    }
    // SAFETY: cpu_set_t is plain data; CPU_ZERO/CPU_SET write within it (cpu < CPU_SETSIZE).
    let r = unsafe {
        let mut set: libc::cpu_set_t = std::mem::zeroed();
        libc::CPU_ZERO(&mut set);
        libc::CPU_SET(cpu, &mut set);
        libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &set)
    };
    os_result(
        r,
        &format!("sched_setaffinity to CPU {cpu}"),
        &format!("this machine has {} CPUs online", cpus_online()),
    )
}

/// Elsewhere: refused.
#[cfg(not(target_os = "linux"))]
pub fn pin_to(_cpu: usize) -> Result<(), String> {
    Err("--pin: sched_setaffinity is Linux only".into())
}

/// Makes the calling thread SCHED_FIFO at `priority` (1..=99): it runs whenever it is ready,
/// ahead of every normal thread (the kernel's RT throttling still leaves others 5 % of each
/// second by default, `/proc/sys/kernel/sched_rt_runtime_us`).
#[cfg(target_os = "linux")]
pub fn fifo(priority: i32) -> Result<(), String> {
    let param = libc::sched_param {
        sched_priority: priority,
    };
    // SAFETY: a valid sched_param for the call; 0 is the calling thread.
    let r = unsafe { libc::sched_setscheduler(0, libc::SCHED_FIFO, &param) };
    os_result(
        r,
        &format!("sched_setscheduler(SCHED_FIFO, {priority})"),
        "needs CAP_SYS_NICE or RLIMIT_RTPRIO",
    )
}

/// Elsewhere: refused.
#[cfg(not(target_os = "linux"))]
pub fn fifo(_priority: i32) -> Result<(), String> {
    Err("--fifo: SCHED_FIFO is Linux only".into())
}

/// mlockall(MCL_CURRENT | MCL_FUTURE): every page of the process resident, now and later.
#[cfg(target_os = "linux")]
pub fn lock_memory() -> Result<(), String> {
    // SAFETY: no pointers; the call only changes the process's paging.
    let r = unsafe { libc::mlockall(libc::MCL_CURRENT | libc::MCL_FUTURE) };
    os_result(
        r,
        "mlockall(MCL_CURRENT | MCL_FUTURE)",
        "RLIMIT_MEMLOCK or missing CAP_IPC_LOCK",
    )
}

/// Elsewhere: refused.
#[cfg(not(target_os = "linux"))]
pub fn lock_memory() -> Result<(), String> {
    Err("--mlock: mlockall is Linux only".into())
}

/// getrusage(`who`), if the kernel answers.
#[cfg(target_os = "linux")]
fn rusage(who: libc::c_int) -> Option<libc::rusage> {
    // SAFETY: rusage is plain data (all zero is a valid value); a valid out-pointer for the call.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: as above.
    (unsafe { libc::getrusage(who, &mut u) } == 0).then_some(u)
}

/// Page faults of the process so far: (minor, major), from getrusage(RUSAGE_SELF); zero if
/// refused.
#[cfg(target_os = "linux")]
pub fn page_faults() -> (u64, u64) {
    rusage(libc::RUSAGE_SELF).map_or((0, 0), |u| (u.ru_minflt as u64, u.ru_majflt as u64))
}

/// Context switches of the calling thread so far: (voluntary, involuntary), from
/// getrusage(RUSAGE_THREAD); zero if refused.
#[cfg(target_os = "linux")]
pub fn context_switches() -> (u64, u64) {
    rusage(libc::RUSAGE_THREAD).map_or((0, 0), |u| (u.ru_nvcsw as u64, u.ru_nivcsw as u64))
}

/// Elsewhere: unknown (zero).
#[cfg(not(target_os = "linux"))]
pub fn page_faults() -> (u64, u64) {
    (0, 0)
}

/// Elsewhere: unknown (zero).
#[cfg(not(target_os = "linux"))]
pub fn context_switches() -> (u64, u64) {
    (0, 0)
}

/// The 1-minute load average (`/proc/loadavg`), if readable: how busy the machine was.
pub fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// CPUs online (`sysconf(_SC_NPROCESSORS_ONLN)`; not the affinity mask, which `--pin` narrows).
#[cfg(target_os = "linux")]
pub fn cpus_online() -> usize {
    // SAFETY: no pointers.
    let n = unsafe { libc::sysconf(libc::_SC_NPROCESSORS_ONLN) };
    usize::try_from(n).unwrap_or(0)
}

/// Elsewhere: the parallelism the standard library sees.
#[cfg(not(target_os = "linux"))]
pub fn cpus_online() -> usize {
    std::thread::available_parallelism().map_or(0, |n| n.get())
}
