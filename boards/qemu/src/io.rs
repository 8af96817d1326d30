//! The demo's peripherals, one set per board: the UART that receives the
//! measurement frames (receive interrupt) and sends the report frames
//! (polled), the two advisory output lines behind embedded-hal's
//! `OutputPin`, and the core clock that times SysTick.
//!
//! | board | UART | receive IRQ | advisory lines | core clock |
//! |---|---|---|---|---|
//! | mps2-an386 / an385 | CMSDK APB UART0 at 0x4000_4000 | 0 (UARTRX0; TX is 1, overruns 12) | FPGAIO LED0 (TA), LED1 (RA): register at 0x4002_8000 | 25 MHz |
//! | microbit (nRF51822) | UART0 at 0x4000_2000 | 2 (the peripheral's id) | GPIO P0.13 (TA), P0.14 (RA): LED matrix rows 1–2 | 16 MHz |
//!
//! The IRQ numbers are QEMU 7.2's wiring (`hw/arm/mps2.c`: `uartirq[] =
//! {0, 2, 4, 18, 20}`, "RX irq number; TX irq is always one greater";
//! `hw/arm/nrf51_soc.c`: `BASE_TO_IRQ(NRF51_UART_BASE)` = 2), which follows
//! the AN385 application note's and the nRF51 reference manual's tables.
//!
//! Registers are reached by volatile access to their fixed addresses: there
//! is no peripheral access crate for the MPS2 FPGA images, and one register
//! block each does not justify the nRF51 one. The addresses are constants
//! of this module, so every unsafe access below is to a device register of
//! this board.

use core::convert::Infallible;

/// A memory-mapped 32-bit device register.
#[derive(Clone, Copy)]
struct Reg(usize);

impl Reg {
    fn read(self) -> u32 {
        // SAFETY: `Reg`s are only made from this module's constants, the
        // addresses of this board's device registers; a volatile 32-bit read
        // of a device register has no other effect than the device's own.
        unsafe { core::ptr::read_volatile(self.0 as *const u32) }
    }
    fn write(self, value: u32) {
        // SAFETY: as in `read`: a device register of this board.
        unsafe { core::ptr::write_volatile(self.0 as *mut u32, value) }
    }
}

/// Bounded wait for the transmitter, so a stuck UART costs a dropped byte,
/// not a hung firmware.
const TX_SPIN_LIMIT: u32 = 100_000;

// ---------------------------------------------------------------------------
// MPS2 (AN385 / AN386): CMSDK APB UART, FPGAIO LEDs
// ---------------------------------------------------------------------------

#[cfg(any(abtrack_board = "mps2-an386", abtrack_board = "mps2-an385"))]
mod board_io {
    use super::{Reg, TX_SPIN_LIMIT};

    pub const CORE_CLOCK_HZ: u32 = 25_000_000;
    /// UARTRX0.
    pub const UART_RX_IRQ: u16 = 0;
    pub const UART_NAME: &str = "CMSDK UART0 at 0x40004000";
    pub const PINS_NAME: &str = "FPGAIO LED0 (TA) and LED1 (RA) at 0x40028000";

    const UART0: usize = 0x4000_4000;
    const DATA: Reg = Reg(UART0);
    const STATE: Reg = Reg(UART0 + 0x04);
    const CTRL: Reg = Reg(UART0 + 0x08);
    const INTSTATUS: Reg = Reg(UART0 + 0x0C);
    const BAUDDIV: Reg = Reg(UART0 + 0x10);
    const STATE_TX_FULL: u32 = 1 << 0;
    const STATE_RX_FULL: u32 = 1 << 1;
    const STATE_RX_OVERRUN: u32 = 1 << 3;
    const CTRL_TX_EN: u32 = 1 << 0;
    const CTRL_RX_EN: u32 = 1 << 1;
    const CTRL_RX_INTEN: u32 = 1 << 3;
    const INT_RX: u32 = 1 << 1;

    /// 115 200 baud, 8N1 (the only frame format of this UART); receive
    /// interrupt on.
    pub fn uart_init() {
        BAUDDIV.write(CORE_CLOCK_HZ / 115_200);
        CTRL.write(CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_INTEN);
    }

    /// The received byte, if there is one. Acknowledges the receive
    /// interrupt first (INTSTATUS is write-one-to-clear), then reads
    /// RXFULL: a byte that arrives after the check raises the interrupt
    /// again, so none is left behind.
    pub fn uart_read() -> Option<u8> {
        INTSTATUS.write(INT_RX);
        if STATE.read() & STATE_RX_FULL != 0 {
            Some(DATA.read() as u8)
        } else {
            None
        }
    }

    /// True (once) if the receiver overran since the last call.
    pub fn uart_overrun() -> bool {
        if STATE.read() & STATE_RX_OVERRUN != 0 {
            STATE.write(STATE_RX_OVERRUN);
            true
        } else {
            false
        }
    }

    /// Sends a byte; false if the transmitter stayed busy.
    pub fn uart_write(byte: u8) -> bool {
        for _ in 0..TX_SPIN_LIMIT {
            if STATE.read() & STATE_TX_FULL == 0 {
                DATA.write(byte as u32);
                return true;
            }
        }
        false
    }

    const LED: Reg = Reg(0x4002_8000);

    /// LED `index` of the FPGAIO LED register.
    pub fn pin_set(index: u8, high: bool) {
        let bit = 1u32 << index;
        let v = LED.read();
        LED.write(if high { v | bit } else { v & !bit });
    }
    pub fn pin_level(index: u8) -> bool {
        LED.read() & (1 << index) != 0
    }
    pub fn pin_init(_index: u8) {}
    pub const TA_PIN: u8 = 0;
    pub const RA_PIN: u8 = 1;
}

// ---------------------------------------------------------------------------
// micro:bit (nRF51822): UART0, GPIO
// ---------------------------------------------------------------------------

/// The Nordic UART (nRF51 UART0 and nRF52840 UART0, the same legacy UART
/// at the same address and offsets: nRF51 Series Reference Manual v3.0
/// §29, nRF52840 Product Specification v1.7 §6.33) and the GPIO port 0
/// output registers, shared by the micro:bit and the nRF52840-DK.
#[cfg(any(abtrack_board = "microbit", abtrack_board = "nrf52840-dk"))]
mod nordic {
    use super::{Reg, TX_SPIN_LIMIT};

    const UART0: usize = 0x4000_2000;
    const TASKS_STARTRX: Reg = Reg(UART0);
    const TASKS_STARTTX: Reg = Reg(UART0 + 0x008);
    const EVENTS_RXDRDY: Reg = Reg(UART0 + 0x108);
    const EVENTS_TXDRDY: Reg = Reg(UART0 + 0x11C);
    const INTENSET: Reg = Reg(UART0 + 0x304);
    const ERRORSRC: Reg = Reg(UART0 + 0x480);
    const ENABLE: Reg = Reg(UART0 + 0x500);
    const PSEL_TXD: Reg = Reg(UART0 + 0x50C);
    const PSEL_RXD: Reg = Reg(UART0 + 0x514);
    const RXD: Reg = Reg(UART0 + 0x518);
    const TXD: Reg = Reg(UART0 + 0x51C);
    const BAUDRATE: Reg = Reg(UART0 + 0x524);
    const ENABLE_UART: u32 = 4;
    const BAUD_115200: u32 = 0x01D7_E000;
    const INT_RXDRDY: u32 = 1 << 2;
    const ERROR_OVERRUN: u32 = 1 << 0;

    /// 115 200 baud 8N1 on pins `tx` and `rx` of port 0; receive
    /// interrupt on.
    pub fn uart_start(tx: u32, rx: u32) {
        PSEL_TXD.write(tx);
        PSEL_RXD.write(rx);
        BAUDRATE.write(BAUD_115200);
        ENABLE.write(ENABLE_UART);
        TASKS_STARTRX.write(1);
        TASKS_STARTTX.write(1);
        INTENSET.write(INT_RXDRDY);
    }

    /// The received byte, if there is one: clear RXDRDY, then read RXD
    /// (which raises RXDRDY again if more bytes wait in the FIFO).
    pub fn uart_read() -> Option<u8> {
        if EVENTS_RXDRDY.read() != 0 {
            EVENTS_RXDRDY.write(0);
            Some(RXD.read() as u8)
        } else {
            None
        }
    }

    /// True (once) if the receiver overran since the last call.
    pub fn uart_overrun() -> bool {
        if ERRORSRC.read() & ERROR_OVERRUN != 0 {
            // ERRORSRC is write-one-to-clear.
            ERRORSRC.write(ERROR_OVERRUN);
            true
        } else {
            false
        }
    }

    /// Sends a byte; false if the transmitter stayed busy.
    pub fn uart_write(byte: u8) -> bool {
        TXD.write(byte as u32);
        for _ in 0..TX_SPIN_LIMIT {
            if EVENTS_TXDRDY.read() != 0 {
                EVENTS_TXDRDY.write(0);
                return true;
            }
        }
        false
    }

    const GPIO_P0: usize = 0x5000_0000;
    pub const OUT: Reg = Reg(GPIO_P0 + 0x504);
    pub const OUTSET: Reg = Reg(GPIO_P0 + 0x508);
    pub const OUTCLR: Reg = Reg(GPIO_P0 + 0x50C);
    pub const DIRSET: Reg = Reg(GPIO_P0 + 0x518);
}

#[cfg(abtrack_board = "microbit")]
mod board_io {
    pub use super::nordic::{uart_overrun, uart_read, uart_write};
    use super::nordic::{DIRSET, OUT, OUTCLR, OUTSET};

    pub const CORE_CLOCK_HZ: u32 = 16_000_000;
    /// UART0 is peripheral id 2.
    pub const UART_RX_IRQ: u16 = 2;
    pub const UART_NAME: &str = "nRF51 UART0 at 0x40002000";
    pub const PINS_NAME: &str = "GPIO P0.13 (TA) and P0.14 (RA)";

    /// 115 200 baud on the micro:bit's USB-serial pins (TX P0.24, RX
    /// P0.25); receive interrupt on.
    pub fn uart_init() {
        super::nordic::uart_start(24, 25);
    }

    pub fn pin_set(index: u8, high: bool) {
        let bit = 1u32 << index;
        if high {
            OUTSET.write(bit);
        } else {
            OUTCLR.write(bit);
        }
    }
    pub fn pin_level(index: u8) -> bool {
        OUT.read() & (1 << index) != 0
    }
    pub fn pin_init(index: u8) {
        DIRSET.write(1 << index);
    }
    pub const TA_PIN: u8 = 13;
    pub const RA_PIN: u8 = 14;
}

// The real board, nRF52840-DK (boards/nrf52840-dk): in its own file.
#[cfg(abtrack_board = "nrf52840-dk")]
mod nrf52840;
#[cfg(abtrack_board = "nrf52840-dk")]
use nrf52840 as board_io;

pub use board_io::{
    uart_init, uart_overrun, uart_read, uart_write, CORE_CLOCK_HZ, PINS_NAME, UART_NAME,
    UART_RX_IRQ,
};

/// The UART's receive interrupt line, for the NVIC.
#[derive(Clone, Copy)]
pub struct UartRxIrq;

// SAFETY: one device interrupt, whose number never changes.
unsafe impl cortex_m::interrupt::InterruptNumber for UartRxIrq {
    fn number(self) -> u16 {
        UART_RX_IRQ
    }
}

/// An advisory output line (embedded-hal 1.0 `OutputPin`).
pub struct AdvisoryPin {
    index: u8,
}

impl AdvisoryPin {
    /// The traffic-advisory line.
    pub fn traffic() -> Self {
        board_io::pin_init(board_io::TA_PIN);
        AdvisoryPin {
            index: board_io::TA_PIN,
        }
    }
    /// The resolution-advisory line.
    pub fn resolution() -> Self {
        board_io::pin_init(board_io::RA_PIN);
        AdvisoryPin {
            index: board_io::RA_PIN,
        }
    }
    /// The level read back from the output register.
    pub fn is_high(&self) -> bool {
        board_io::pin_level(self.index)
    }
}

impl embedded_hal::digital::ErrorType for AdvisoryPin {
    type Error = Infallible;
}

impl embedded_hal::digital::OutputPin for AdvisoryPin {
    fn set_low(&mut self) -> Result<(), Infallible> {
        board_io::pin_set(self.index, false);
        Ok(())
    }
    fn set_high(&mut self) -> Result<(), Infallible> {
        board_io::pin_set(self.index, true);
        Ok(())
    }
}
