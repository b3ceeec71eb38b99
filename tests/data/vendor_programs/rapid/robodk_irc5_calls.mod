%%%
  VERSION:1
  LANGUAGE:ENGLISH
%%%

MODULE MOD_Main
    
    LOCAL PERS tooldata rdkTool := [TRUE,[[0,0,0],[1,0,0,0]],[2,[0,0,15],[1,0,0,0],0,0,0.005]];
    LOCAL PERS wobjdata rdkWObj := [FALSE, TRUE, "", [[0,0,0],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
    VAR speeddata rdkSpeed := [250,500,5000,1000]; ! set default speed

    ! -------------------------------
    ! Define your variables here
    ! ...


    ! -------------------------------
    ! Define your functions here
    ! ...

    
    PROC Main()
        ConfJ \On;
        ConfL \Off;
        rdkWObj.uframe := [[100.000, -50.000, 20.000],[0.70710678, 0.00000000, 0.00000000, 0.70710678]];
        rdkTool.tframe := [[0.000, 0.000, 150.000],[1.00000000, 0.00000000, 0.00000000, 0.00000000]];
        rdkSpeed := [500.00,500,5000,1000];
        MoveAbsJ [[-46.184190,-6.775180,-20.549250,71.386740,49.587270,-102.547520],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],rdkSpeed,z10,rdkTool,\WObj:=rdkWObj;
        Pick;
        MoveL [[500.000, 250.000, 348.735],[0.00000000, 0.25881905, -0.96592583, 0.00000000],[-1,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],rdkSpeed,z0,rdkTool,\WObj:=rdkWObj;
        WaitDI D_IN_3, 1, \MaxTime:=2.0;
        SetDO D_OUT_2, 0;
        Place;
        MoveAbsJ [[-46.184190,-6.775180,-20.549250,71.386740,49.587270,-102.547520],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],rdkSpeed,z0,rdkTool,\WObj:=rdkWObj;
    ENDPROC

    
    PROC Pick()
        ConfJ \On;
        ConfL \Off;
        rdkSpeed := [100.00,500,5000,1000];
        MoveL [[500.000, 200.000, 262.132],[0.00000000, 0.25881905, -0.96592583, 0.00000000],[-1,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],rdkSpeed,z0,rdkTool,\WObj:=rdkWObj;
        SetDO D_OUT_1, 1;
        WaitTime 0.500;
        MoveL [[500.000, 250.000, 348.735],[0.00000000, 0.25881905, -0.96592583, 0.00000000],[-1,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],rdkSpeed,z0,rdkTool,\WObj:=rdkWObj;
    ENDPROC

    
    PROC Place()
        ConfJ \On;
        ConfL \Off;
        MoveL [[550.000, 300.000, 278.024],[0.00000000, 0.25881905, -0.96592583, 0.00000000],[-1,0,-1,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]],rdkSpeed,z0,rdkTool,\WObj:=rdkWObj;
        SetDO D_OUT_1, 0;
        WaitTime 0.500;
    ENDPROC

ENDMODULE
