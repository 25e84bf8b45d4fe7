//! How much fresh memory a stretch of the process faulted in (Linux). A call that allocates its
//! working memory gets pages no one has used since the system gave them out: the first write to
//! each one faults, and the kernel zeroes the page before handing it over (2 MiB at a time where
//! the memory came in transparent huge pages). That cost is the call's, and a caller's scratch
//! kept between calls does not pay it.

use std::fs;

/// Base and huge page sizes on the systems the library asks for huge pages on (x86-64, AArch64
/// with 4 KiB pages).
const PAGE: u64 = 4096;
const HUGE_PAGE: u64 = 2 << 20;

/// Page faults so far: the process's minor faults (every thread's, each fault one, whatever it
/// mapped) and the system's huge pages allocated at a fault.
#[derive(Clone, Copy)]
pub struct Faults {
    minor: u64,
    huge: u64,
}

/// Fresh memory faulted in between two [`Faults`].
pub struct Fresh {
    pub huge_faults: u64,
    pub other_faults: u64,
}

impl Fresh {
    /// Bytes: a huge page per huge fault, a base page per other one.
    pub fn bytes(&self) -> u64 {
        self.huge_faults * HUGE_PAGE + self.other_faults * PAGE
    }
}

impl Faults {
    /// The counts now, or `None` where `/proc` does not give them. The huge-page count is the
    /// whole system's (`thp_fault_alloc` in `/proc/vmstat`): on a machine busy with other work it
    /// counts theirs too.
    pub fn now() -> Option<Faults> {
        let stat = fs::read_to_string("/proc/self/stat").ok()?;
        // Fields after the command name (which may hold spaces): state, ppid, pgrp, session,
        // tty_nr, tpgid, flags, minflt.
        let minor = stat.rsplit_once(')')?.1.split_whitespace().nth(7)?.parse().ok()?;
        let vmstat = fs::read_to_string("/proc/vmstat").ok()?;
        let huge = vmstat
            .lines()
            .find_map(|line| line.strip_prefix("thp_fault_alloc "))
            .map_or(Some(0), |n| n.trim().parse().ok())?;
        Some(Faults { minor, huge })
    }

    /// What was faulted in since `earlier`.
    pub fn since(&self, earlier: &Faults) -> Fresh {
        let huge_faults = self.huge.saturating_sub(earlier.huge);
        let minor = self.minor.saturating_sub(earlier.minor);
        Fresh {
            huge_faults,
            other_faults: minor.saturating_sub(huge_faults),
        }
    }
}
