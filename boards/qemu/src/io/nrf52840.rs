//! The demo's peripherals on the nRF52840-DK (PCA10056): the same small
//! interface as the emulated boards' in `io.rs` (which uses this module as
//! its `board_io` for `cfg(abtrack_board = "nrf52840-dk")`).
//!
//! | part | nRF52840-DK |
//! |---|---|
//! | UART | UART0 at 0x4000_2000, 115 200 baud 8N1, TXD P0.06, RXD P0.08: the J-Link OB's virtual COM port (USB) |
//! | receive IRQ | 2 (UARTE0_UART0) |
//! | advisory lines | LED1 = P0.13 (TA), LED2 = P0.14 (RA), lit when the advisory is on (the LEDs are active low) |
//! | core clock | 64 MHz; the UART's clock from the 32 MHz crystal (HFXO) |
//!
//! Register offsets and values from the nRF52840 Product Specification v1.7:
//! UART (§6.33, the non-EasyDMA UART, which reads one byte per interrupt as
//! the demo's receiver expects), GPIO (§6.9), CLOCK (§6.4). Pins from the
//! nRF52840-DK user guide (UART and LED tables). Direct register access, as
//! for the emulated boards: four registers of three peripherals do not
//! justify a HAL.

pub use super::nordic::{uart_overrun, uart_read, uart_write};
use super::nordic::{DIRSET, OUT, OUTCLR, OUTSET};
use super::Reg;

pub const CORE_CLOCK_HZ: u32 = 64_000_000;
/// UARTE0_UART0 is peripheral id 2.
pub const UART_RX_IRQ: u16 = 2;
pub const UART_NAME: &str = "nRF52840 UART0 at 0x40002000 (DK virtual COM port)";
pub const PINS_NAME: &str = "LED1 P0.13 (TA) and LED2 P0.14 (RA)";

const CLOCK: usize = 0x4000_0000;
const TASKS_HFCLKSTART: Reg = Reg(CLOCK);
const EVENTS_HFCLKSTARTED: Reg = Reg(CLOCK + 0x100);

const TXD_PIN: u32 = 6;
const RXD_PIN: u32 = 8;

/// Bounded wait for the crystal: without it the UART runs on the internal
/// oscillator, whose tolerance is marginal for 115 200 baud.
const HFXO_SPIN_LIMIT: u32 = 1_000_000;

/// 115 200 baud on the DK's virtual COM port; receive interrupt on.
pub fn uart_init() {
    TASKS_HFCLKSTART.write(1);
    for _ in 0..HFXO_SPIN_LIMIT {
        if EVENTS_HFCLKSTARTED.read() != 0 {
            break;
        }
    }
    super::nordic::uart_start(TXD_PIN, RXD_PIN);
}

/// Sets advisory line `index` on (`high`) or off. The DK's LEDs light when
/// their pin is low, so "on" drives the pin low.
pub fn pin_set(index: u8, high: bool) {
    let bit = 1u32 << index;
    if high {
        OUTCLR.write(bit);
    } else {
        OUTSET.write(bit);
    }
}

/// Whether advisory line `index` is on (its pin driven low).
pub fn pin_level(index: u8) -> bool {
    OUT.read() & (1 << index) == 0
}

/// An output, off (pin high: LED dark).
pub fn pin_init(index: u8) {
    OUTSET.write(1 << index);
    DIRSET.write(1 << index);
}

pub const TA_PIN: u8 = 13;
pub const RA_PIN: u8 = 14;
