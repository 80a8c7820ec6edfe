//! Function sizes from a static library's ELF symbol tables.

/// (name, size) of every function symbol of the ELF32 little-endian objects of an `ar` archive.
/// A few lines for the one question the test asks, rather than an object-file crate.
pub(crate) fn symbol_sizes(archive: &[u8]) -> Vec<(String, u32)> {
    assert_eq!(&archive[..8], b"!<arch>\n", "not an ar archive");
    let u16_at = |b: &[u8], at: usize| u16::from_le_bytes([b[at], b[at + 1]]) as usize;
    let u32_at = |b: &[u8], at: usize| u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]);
    let mut out = Vec::new();
    let mut at = 8;
    while at + 60 <= archive.len() {
        let size: usize = std::str::from_utf8(&archive[at + 48..at + 58]).unwrap().trim().parse().unwrap();
        let elf = &archive[at + 60..at + 60 + size];
        at += 60 + size + size % 2;
        if elf.len() < 52 || &elf[..4] != b"\x7fELF" || elf[4] != 1 || elf[5] != 1 {
            continue;
        }
        let (shoff, shentsize, shnum) = (u32_at(elf, 0x20) as usize, u16_at(elf, 0x2e), u16_at(elf, 0x30));
        let section = |k: usize| &elf[shoff + k * shentsize..shoff + (k + 1) * shentsize];
        for k in 0..shnum {
            let sh = section(k);
            if u32_at(sh, 4) != 2 {
                continue; // not SHT_SYMTAB
            }
            let (offset, bytes) = (u32_at(sh, 16) as usize, u32_at(sh, 20) as usize);
            let strings = section(u32_at(sh, 24) as usize);
            let strtab = &elf[u32_at(strings, 16) as usize..][..u32_at(strings, 20) as usize];
            for sym in elf[offset..offset + bytes].chunks_exact(16) {
                if sym[12] & 0xf != 2 {
                    continue; // not STT_FUNC
                }
                let name = &strtab[u32_at(sym, 0) as usize..];
                let name = String::from_utf8_lossy(&name[..name.iter().position(|&c| c == 0).unwrap_or(0)]).into_owned();
                out.push((name, u32_at(sym, 8)));
            }
        }
    }
    out
}
