import sys,re,subprocess
fn=None; out={}; count=0
for line in open(sys.argv[1]):
    m=re.match(r"^[0-9a-f]+ <(.*)>:$", line)
    if m: fn=m.group(1); count=0; out[fn]=0; continue
    count+=1
    if count>30 or fn is None: continue
    m=re.search(r"sub\s+\$0x([0-9a-f]+),%rsp", line)
    if m: out[fn]+=int(m.group(1),16)
    m=re.search(r"sub\s+\$0x([0-9a-f]+),%r11", line)
    if m: out[fn]+=int(m.group(1),16)
items=sorted(((v,f) for f,v in out.items() if v>int(sys.argv[2])), reverse=True)
names=subprocess.run(["c++filt"],input="\n".join(f for _,f in items),capture_output=True,text=True).stdout.split("\n")
for (v,_),n in zip(items,names): print(v//1024, "KiB", re.sub(r"::h[0-9a-f]{16}$","",n)[:160])
